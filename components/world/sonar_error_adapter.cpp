#include "world/sonar_error_adapter.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace stickrep::world {

sensing::Surface ToSensingSurface(SurfaceType surface) {
  switch (surface) {
    case SurfaceType::kConcrete:
      return sensing::Surface::kConcrete;
    case SurfaceType::kWood:
      return sensing::Surface::kWood;
    case SurfaceType::kCloth:
      return sensing::Surface::kCloth;
  }
  return sensing::Surface::kConcrete;
}

SurfaceType FromSensingSurface(sensing::Surface surface) {
  switch (surface) {
    case sensing::Surface::kConcrete:
      return SurfaceType::kConcrete;
    case sensing::Surface::kWood:
      return SurfaceType::kWood;
    case sensing::Surface::kCloth:
      return SurfaceType::kCloth;
  }
  return SurfaceType::kConcrete;
}

SurfaceTableSonarErrorModel::SurfaceTableSonarErrorModel(SurfaceTableErrorOptions options)
    : options_(options) {
  if (!(options_.max_range_in > 0.0) || !std::isfinite(options_.max_range_in)) {
    throw std::invalid_argument("sonar error model: max_range_in must be finite and > 0 in");
  }
}

std::optional<double> SurfaceTableSonarErrorModel::Apply(double true_range_in, SurfaceType surface,
                                                         double incidence_rad,
                                                         std::mt19937_64& rng) const {
  if (!std::isfinite(true_range_in) || true_range_in < 0.0 || !std::isfinite(incidence_rad)) {
    return std::nullopt;
  }
  sensing::UltrasoundExperiment which = sensing::UltrasoundExperiment::kTable42;
  switch (options_.table) {
    case UltrasoundTable::kTable42:
      break;
    case UltrasoundTable::kTable43:
      which = sensing::UltrasoundExperiment::kTable43;
      break;
    case UltrasoundTable::kMixtureOfBoth:
      if (std::uniform_int_distribution<int>(0, 1)(rng) == 1) {
        which = sensing::UltrasoundExperiment::kTable43;
      }
      break;
  }
  const std::optional<sensing::PercentRangeError> cell =
      sensing::SurfaceRangeError(ToSensingSurface(surface), incidence_rad, which);
  if (!cell) {
    if (options_.gross == GrossReading::kLost || true_range_in >= options_.max_range_in) {
      return std::nullopt;
    }
    return std::uniform_real_distribution<double>(true_range_in, options_.max_range_in)(rng);
  }
  // Never early: a draw below zero (cloth at 15°: 85 +- 80 %) is the earliest echo.
  const double e_pct =
      std::max(0.0, std::normal_distribution<double>(cell->mean_pct, cell->sigma_pct)(rng));
  return true_range_in * (1.0 + e_pct / 100.0);
}

}  // namespace stickrep::world
