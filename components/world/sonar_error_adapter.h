#pragma once

#include <optional>
#include <random>

#include "sensing/sonar_model.h"
#include "world/sonar_ring.h"
#include "world/world.h"

namespace stickrep::world {

// The world's surface classes and the sensing library's are the same three surfaces of the
// ultrasound study (§4.3); these convert between the two enums.
sensing::Surface ToSensingSurface(SurfaceType surface);
SurfaceType FromSensingSurface(sensing::Surface surface);

// Which repetition of the ultrasound study drives the simulated error.
enum class UltrasoundTable {
  kTable42,  // experiment 1 only
  kTable43,  // experiment 2 only
  // Each reading draws experiment 1 or 2 with equal odds: a two-component Gaussian mixture
  // per cell, the text's "multimodal Gaussian error models ... developed from the
  // ultrasonic sensing analysis" (§4.3) with both repetitions weighted alike.
  kMixtureOfBoth,
};

// What a "++" cell (gross error: cloth beyond 30°, any surface beyond 45°) returns.
enum class GrossReading {
  kLost,        // no echo: the reading is invalid
  kRandomLong,  // a spurious late echo, uniform between the true range and max_range_in
};

struct SurfaceTableErrorOptions {
  UltrasoundTable table = UltrasoundTable::kMixtureOfBoth;
  GrossReading gross = GrossReading::kLost;
  double max_range_in = 420.0;  // §4.3: 35 ft; only used by kRandomLong
};

// Sonar range error from the surface/incidence tables of §4.3 (Tables 4.2, 4.3, through
// sensing::SurfaceRangeError), for the world's sonar ring simulator. A reading at incidence
// phi on a surface reports true * (1 + e / 100) with e ~ N(mean %, sigma %) of that cell,
// interpolated between the tabulated 0/15/30/45°. The error is taken as a lengthening: the
// tables give magnitudes without a sign, and an oblique or absorbing surface returns its
// first echo late, never early (the nearest point in the cone is already the earliest
// echo the geometry allows, §5.4).
class SurfaceTableSonarErrorModel final : public SonarErrorModel {
 public:
  explicit SurfaceTableSonarErrorModel(SurfaceTableErrorOptions options = {});

  std::optional<double> Apply(double true_range_in, SurfaceType surface, double incidence_rad,
                              std::mt19937_64& rng) const override;

  const SurfaceTableErrorOptions& options() const { return options_; }

 private:
  SurfaceTableErrorOptions options_;
};

}  // namespace stickrep::world
