#pragma once

namespace stickrep::localizer {

// The Bayes filter's posterior is over-confident: it weighs each sensed edge as if its
// errors were independent of the others', and on the landmark pipeline they are not (a dark
// door's casing misread on one door tends to be misread on the next). Measured over many
// seeded runs, the share of poses that were right at posterior p follows a logistic curve
// in the log-odds (Platt scaling):
//
//   logit(confidence) = slope * logit(posterior) + offset
//
// The localizer publishes the calibrated confidence, and the LOCALIZED threshold is set on
// it: 1 - threshold is the stated risk that a declared pose names the wrong place
// (docs/whereami.md, "Reliability of the published confidence"). slope 1, offset 0 leaves
// the posterior as it is.
struct ConfidenceCalibration {
  double slope = 1.0;
  double offset = 0.0;

  // The calibrated confidence of a posterior (both in [0, 1]; monotonic for slope > 0).
  double Calibrated(double posterior) const;
  // The posterior whose calibrated confidence is `confidence` (the inverse).
  double PosteriorFor(double confidence) const;
};

}  // namespace stickrep::localizer
