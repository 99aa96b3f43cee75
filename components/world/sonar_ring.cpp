#include "world/sonar_ring.h"

#include <cmath>
#include <stdexcept>

#include "common/units.h"

namespace stickrep::world {

SonarRingSimulator::SonarRingSimulator(SonarRingModel model) : model_(model) {
  if (model_.count <= 0 || !(model_.cone_deg > 0.0 && model_.cone_deg < 180.0) ||
      !(model_.min_range_in >= 0.0 && model_.max_range_in > model_.min_range_in) ||
      !(model_.head_radius_in >= 0.0)) {
    throw std::invalid_argument(
        "sonar ring: need count > 0, 0 < cone_deg < 180, 0 <= min_range_in < max_range_in, "
        "head_radius_in >= 0");
  }
}

double SonarRingSimulator::SensorBearing(const Pose2d& X_WR, int k) const {
  return X_WR.theta_rad + DegToRad(model_.coaxial_yaw_deg - k * model_.spacing_deg);
}

std::vector<SonarReading> SonarRingSimulator::Sense(const Scene& scene, const Pose2d& X_WR,
                                                    const SonarErrorModel& error_model,
                                                    std::mt19937_64& rng) const {
  std::vector<SonarReading> out(model_.count);
  const double half_cone = DegToRad(model_.cone_deg) / 2.0;
  for (int k = 0; k < model_.count; ++k) {
    SonarReading& r = out[k];
    r.bearing_rad = SensorBearing(X_WR, k);
    const Eigen::Vector2d axis{std::cos(r.bearing_rad), std::sin(r.bearing_rad)};
    const Eigen::Vector2d face = X_WR.position() + axis * model_.head_radius_in;
    const std::optional<ConeHit> hit =
        scene.NearestInCone(face, axis, half_cone, model_.max_range_in, model_.height_in);
    if (!hit) continue;
    r.true_range_in = hit->distance_in;
    r.incidence_rad = hit->incidence_rad;
    r.surface = hit->surface;
    const std::optional<double> reported =
        error_model.Apply(hit->distance_in, hit->surface, hit->incidence_rad, rng);
    if (!reported || !std::isfinite(*reported)) continue;
    r.range_in = *reported;
    r.valid = r.range_in >= model_.min_range_in && r.range_in <= model_.max_range_in;
  }
  return out;
}

std::vector<SonarReading> SonarRingSimulator::SenseExact(const Scene& scene,
                                                         const Pose2d& X_WR) const {
  std::mt19937_64 unused(0);
  return Sense(scene, X_WR, ExactSonarErrorModel{}, unused);
}

}  // namespace stickrep::world
