#include "sensing/sonar_model.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/units.h"

namespace stickrep::sensing {

SonarRingModel SonarRingModel::FromConfig(const RobotConfig& c) {
  SonarRingModel m;
  m.count = c.sonar_ring.count;
  m.spacing_rad = DegToRad(c.sonar_ring.spacing_deg);
  m.head_radius_in = c.sonar_ring.head_radius_in;
  m.half_cone_rad = DegToRad(c.sonar_ring.cone_deg) / 2.0;
  m.min_range_in = c.sonar_ring.min_range_in;
  m.max_range_in = c.sonar_ring.max_range_in;
  m.footprint_rad = DegToRad(c.sonar_ring.footprint_deg);
  m.coaxial_sensor = c.camera.coaxial_sensor;
  return m;
}

double SonarRingModel::BearingOf(int k) const {
  double b = (k - coaxial_sensor) * spacing_rad;
  b = std::remainder(b, 2.0 * kPi);  // into [-pi, pi]
  if (b <= -kPi) b += 2.0 * kPi;
  return b;
}

bool SonarRingModel::InRange(double range_in) const {
  return std::isfinite(range_in) && range_in >= min_range_in && range_in <= max_range_in;
}

ReturnCase ClassifyReturn(const SonarRingModel& ring, double incidence_rad) {
  const double off = std::abs(incidence_rad);
  if (off <= ring.half_cone_rad) return ReturnCase::kNormalInsideCone;
  if (off - ring.half_cone_rad < kPi / 2.0) return ReturnCase::kNormalOutsideCone;
  return ReturnCase::kNoEcho;
}

Result<double> ReturnedRange(const SonarRingModel& ring, double wall_distance_in,
                             double incidence_rad) {
  if (!std::isfinite(wall_distance_in) || !std::isfinite(incidence_rad) ||
      wall_distance_in <= 0.0) {
    return Result<double>::Fail(SensingError::kBadParameter,
                                "wall distance and incidence must be finite, distance > 0");
  }
  const double perpendicular = wall_distance_in - ring.head_radius_in * std::cos(incidence_rad);
  if (perpendicular <= 0.0) {
    return Result<double>::Fail(SensingError::kDegenerateGeometry,
                                "the wall is inside the sonar head");
  }
  switch (ClassifyReturn(ring, incidence_rad)) {
    case ReturnCase::kNormalInsideCone:
      return Result<double>::Ok(perpendicular);
    case ReturnCase::kNormalOutsideCone:
      return Result<double>::Ok(perpendicular /
                                std::cos(std::abs(incidence_rad) - ring.half_cone_rad));
    case ReturnCase::kNoEcho:
      break;
  }
  return Result<double>::Fail(SensingError::kDegenerateGeometry,
                              "the sensor cone points away from the wall: no echo");
}

Result<double> RangeAlongRay(const SonarRingModel& ring, double returned_in,
                             double sensor_incidence_rad, double ray_incidence_rad) {
  if (!std::isfinite(returned_in) || returned_in <= 0.0) {
    return Result<double>::Fail(SensingError::kBadSonarRange, "returned range must be > 0 in");
  }
  if (!std::isfinite(ray_incidence_rad) || std::abs(ray_incidence_rad) >= kPi / 2.0 ||
      ClassifyReturn(ring, sensor_incidence_rad) == ReturnCase::kNoEcho) {
    return Result<double>::Fail(SensingError::kDegenerateGeometry,
                                "the ray or the sensor does not meet the wall");
  }
  const double outside = std::max(0.0, std::abs(sensor_incidence_rad) - ring.half_cone_rad);
  const double wall_distance =
      returned_in * std::cos(outside) + ring.head_radius_in * std::cos(sensor_incidence_rad);
  return Result<double>::Ok(wall_distance / std::cos(ray_incidence_rad));
}

PrintedCaseRanges PrintedExactRanges(double d_l, double d_r, double delta, double fov, double r) {
  auto s = [](double deg) { return std::sin(DegToRad(deg)); };
  const double h = fov / 2.0;
  PrintedCaseRanges out;
  if (delta >= 48.0 && delta < 72.0) {
    out.case_number = 1;
    out.rl_in = d_l / s(delta + h) + s(150 - delta) / s(delta + h) * r;
    out.rr_in = d_r / s(180 - delta + h) + s(delta - 30) / s(180 - delta + h) * r;
  } else if (delta >= 72.0 && delta <= 90.0) {
    out.case_number = 2;
    out.rl_in = s(18 + delta) / s(delta + h) * d_l + s(150 - delta) / s(delta + h) * r;
    out.rr_in = s(198 - delta) / s(180 + h - delta) * d_r + s(delta - 30) / s(180 + h - delta) * r;
  } else if (delta < 48.0) {
    out.case_number = 3;
    out.rl_in = s(138 - delta) * s(150 - delta) / (s(delta + 30) * s(delta + h)) * d_l +
                s(150 - delta) / s(delta + h) * r;
    out.rr_in =
        s(delta + h - 72) * s(delta - 60 + h) / (s(240 - delta - h) * s(210 - delta)) * d_r +
        s(delta - 60 + h) / s(210 - delta) * r;
  }
  return out;
}

const char* ToString(Surface s) {
  switch (s) {
    case Surface::kCloth:
      return "cloth";
    case Surface::kWood:
      return "wood";
    case Surface::kConcrete:
      return "concrete";
  }
  return "unknown";
}

std::optional<Surface> SurfaceFromString(const std::string& name) {
  if (name == "cloth") return Surface::kCloth;
  if (name == "wood") return Surface::kWood;
  if (name == "concrete") return Surface::kConcrete;
  return std::nullopt;
}

namespace {

// One cell of Tables 4.2/4.3; mean < 0 marks "++" (gross error).
struct Cell {
  double mean_pct;
  double sigma_pct;
};
constexpr double kGross = -1.0;
constexpr int kAngles = 4;  // phi = 0, 15, 30, 45 degrees

// [surface][angle]: cloth, wood, concrete as in the tables' column order.
constexpr Cell kTable42[3][kAngles] = {
    {{0.50, 0.03}, {85, 80}, {340, 93}, {kGross, 0}},
    {{0.03, 0.03}, {0.95, 0.03}, {16, 0.07}, {17, 0.08}},
    {{0.71, 0.03}, {2.2, 0.03}, {5, 0.04}, {14, 0.09}},
};
constexpr Cell kTable43[3][kAngles] = {
    {{0.53, 0.03}, {100, 95}, {390, 84}, {kGross, 0}},
    {{0.04, 0.03}, {1.2, 0.04}, {8.9, 0.06}, {22, 0.9}},
    {{0.6, 0.03}, {1.5, 0.03}, {4.3, 0.02}, {15, 0.08}},
};

std::optional<PercentRangeError> FromTable(const Cell (&table)[3][kAngles], Surface s,
                                           double phi_deg) {
  const auto& row = table[static_cast<int>(s)];
  const double pos = phi_deg / 15.0;
  const int i = std::min(static_cast<int>(pos), kAngles - 2);
  const double t = pos - i;
  const Cell& a = row[i];
  const Cell& b = row[i + 1];
  if (a.mean_pct < 0 || (t > 0 && b.mean_pct < 0)) return std::nullopt;
  return PercentRangeError{a.mean_pct + t * (b.mean_pct - a.mean_pct),
                           a.sigma_pct + t * (b.sigma_pct - a.sigma_pct)};
}

}  // namespace

std::optional<PercentRangeError> SurfaceRangeError(Surface s, double phi_rad,
                                                   UltrasoundExperiment which) {
  const double phi_deg = std::abs(RadToDeg(phi_rad));
  if (!std::isfinite(phi_deg) || phi_deg > 45.0 + 1e-9) return std::nullopt;
  switch (which) {
    case UltrasoundExperiment::kTable42:
      return FromTable(kTable42, s, phi_deg);
    case UltrasoundExperiment::kTable43:
      return FromTable(kTable43, s, phi_deg);
    case UltrasoundExperiment::kWorseOfBoth: {
      const auto a = FromTable(kTable42, s, phi_deg);
      const auto b = FromTable(kTable43, s, phi_deg);
      if (!a || !b) return std::nullopt;
      return a->mean_pct >= b->mean_pct ? a : b;
    }
  }
  return std::nullopt;
}

bool InAccurateFootprint(const SonarRingModel& ring, Surface s, double phi_rad) {
  const double phi = std::abs(phi_rad);
  if (s == Surface::kCloth) return phi <= DegToRad(1.0);
  return phi <= ring.footprint_rad;
}

}  // namespace stickrep::sensing
