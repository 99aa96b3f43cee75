#pragma once

// One calibration for several floors: the published confidences of stickrep-whereami batches
// (their --json files, each run on one map) pooled into one Platt fit, and that fit taken
// through the calibration the batches ran under. A floor the shipped configuration names has
// a calibration of its own; a floor it does not (an unseen building) takes the default one,
// which is only as general as the floors it was fitted on.

#include <ostream>
#include <string>
#include <vector>

#include "localizer/confidence_calibration.h"
#include "whereami_tool/integrity_report.h"

namespace stickrep::whereami {

struct PooledCalibrationFit {
  struct Batch {
    std::string file;
    std::string map;
    int runs = 0;
    int samples = 0;
    Reliability::Fit fit;  // the batch's own fit
  };
  std::vector<Batch> batches;
  Reliability::Fit fit;                        // over every batch's samples
  localizer::ConfidenceCalibration ran_under;  // the batches' calibration (one for all)
  localizer::ConfidenceCalibration composed;   // the fit taken through it
  double localized_confidence = 0.0;           // the bar the batches declared poses at
};

// The calibration that makes `fit` the identity for a localizer that published its
// confidence under `ran_under`: logit(right) = a (s logit(p) + o) + b, so slope a s and
// offset a o + b.
localizer::ConfidenceCalibration ComposeCalibration(
    const localizer::ConfidenceCalibration& ran_under, const Reliability::Fit& fit);

// Reads the batches' JSON files (stickrep-whereami --json): each run's published confidences
// and the calibration and bar the batch ran under. Throws InputError (file, key, reason) for a
// file that cannot be read, lacks those keys or ran under another calibration or bar than the
// first.
PooledCalibrationFit FitCalibrationFromBatches(const std::vector<std::string>& files);

void PrintPooledCalibrationFit(const PooledCalibrationFit& f, std::ostream& out);

}  // namespace stickrep::whereami
