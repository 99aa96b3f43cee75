#include "localizer/confidence_calibration.h"

#include <algorithm>
#include <cmath>

namespace stickrep::localizer {

namespace {

// Probabilities this close to 0 or 1 are the filter's floor and ceiling: the log-odds stay
// finite (about ±34.5).
constexpr double kEps = 1e-15;

double Logit(double p) {
  p = std::clamp(p, kEps, 1.0 - kEps);
  return std::log(p / (1.0 - p));
}

double Logistic(double x) { return 1.0 / (1.0 + std::exp(-x)); }

}  // namespace

double ConfidenceCalibration::Calibrated(double posterior) const {
  if (slope == 1.0 && offset == 0.0) return posterior;
  return Logistic(slope * Logit(posterior) + offset);
}

double ConfidenceCalibration::PosteriorFor(double confidence) const {
  if (slope == 1.0 && offset == 0.0) return confidence;
  return Logistic((Logit(confidence) - offset) / slope);
}

}  // namespace stickrep::localizer
