#include "locomotion/hallway_follower.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "common/quantile.h"
#include "common/units.h"

namespace stickrep::locomotion {
namespace {

double WrapPi(double a) { return std::remainder(a, 2.0 * kPi); }

// One valid reading on a side, with its bearing.
struct Reading {
  double bearing_rad;
  double range_in;
};

// The wall distance from the base centre that `r` implies when the wall's normal points
// along `normal_rad` (inverse of PredictedWallRangeIn); NaN beyond a grazing incidence,
// where the cone model says nothing useful.
double ImpliedDistanceIn(const Reading& r, double normal_rad, const HallwayFollowerConfig& c) {
  const double half_cone = DegToRad(c.cone_deg) / 2.0;
  const double phi = std::abs(WrapPi(r.bearing_rad - normal_rad));
  const double beyond = std::max(0.0, phi - half_cone);
  if (beyond >= DegToRad(80.0)) return std::nan("");
  return r.range_in * std::cos(beyond) + c.head_radius_in * std::cos(phi);
}

struct SideFit {
  double distance_in = 0.0;
  double cost = 0.0;
  int inliers = 0;
  int outliers = 0;
  bool oblique_inlier = false;  // an inlier read outside the centre of its cone
};

// Fits one side for a given wall normal: the median implied distance is the consensus (a
// door recess or a person is seen by fewer sensors than the wall around it), the inliers'
// mean refines it, and the truncated squared residuals score the normal.
SideFit FitSide(const std::vector<Reading>& readings, double normal_rad,
                const HallwayFollowerConfig& c) {
  SideFit fit;
  std::vector<double> implied;
  implied.reserve(readings.size());
  for (const Reading& r : readings) {
    const double d = ImpliedDistanceIn(r, normal_rad, c);
    if (std::isfinite(d)) implied.push_back(d);
  }
  if (implied.empty()) return fit;
  const double consensus = Median(implied);
  const double band2 = c.inlier_band_in * c.inlier_band_in;
  double inlier_sum = 0.0;
  const double half_cone = DegToRad(c.cone_deg) / 2.0;
  for (const Reading& r : readings) {
    const double d = ImpliedDistanceIn(r, normal_rad, c);
    if (!std::isfinite(d)) continue;
    const double e2 = (d - consensus) * (d - consensus);
    fit.cost += std::min(e2, band2);
    if (e2 <= band2) {
      ++fit.inliers;
      inlier_sum += d;
      if (std::abs(WrapPi(r.bearing_rad - normal_rad)) > half_cone) fit.oblique_inlier = true;
    } else {
      ++fit.outliers;
    }
  }
  fit.distance_in = fit.inliers > 0 ? inlier_sum / fit.inliers : consensus;
  return fit;
}

// Distance to the nearest echo not explained by the fitted side walls, within the front
// sensors of travel bearing `travel_rad`; and whether those echoes form one wall across.
// The implied distances of `readings` to a wall whose normal points along `normal_rad`, the
// unexplained ones dropped; their median when at least `need` agree within the spread.
double AgreedWallDistance(const std::vector<Reading>& readings, double normal_rad, size_t need,
                          const HallwayFollowerConfig& c) {
  std::vector<double> implied;
  for (const Reading& r : readings) {
    const double d = ImpliedDistanceIn(r, normal_rad, c);
    if (std::isfinite(d)) implied.push_back(d);
  }
  if (implied.size() < need) return kNoObstacle;
  const auto [lo, hi] = std::minmax_element(implied.begin(), implied.end());
  return *hi - *lo <= c.wall_ahead_spread_in ? Median(implied) : kNoObstacle;
}

// What lies ahead in one travel direction.
struct Ahead {
  double free_in = kNoObstacle;
  double wall_in = kNoObstacle;
  double wall_normal_rad = 0.0;
};

// An echo off the front sensors' fan, `off_rad` from the travel direction at `range_in`
// from its transducer's face, that no fitted side wall explains (a convex corner, a column,
// the edge of an opening): the distance along the travel direction at which it stands when
// it lies within the base's swept path (its radius plus swept_clearance_in either side of
// the travel line), taking the direction in the cone nearest the travel axis; no obstacle
// otherwise. The front sensors alone miss a corner met at a slant, which then passes the
// base's flank closer than the sonar's minimum range.
double InSweptPathIn(double off_rad, double range_in, const HallwayFollowerConfig& c) {
  const double nearest = std::max(0.0, off_rad - DegToRad(c.cone_deg) / 2.0);
  const double from_centre = c.head_radius_in + range_in;
  if (from_centre * std::sin(nearest) >= c.head_radius_in + c.swept_clearance_in)
    return kNoObstacle;
  return from_centre * std::cos(nearest);
}

// A wall at another angle than across (the hallway turns by less than a right angle), its
// normal searched outward from the axis. A reading fits every plane whose normal lies in its
// cone, so the sensors agree over a run of angles around the true one: the run found first
// (the smallest angle three sensors agree on, one of them a front sensor) is taken and its
// middle is the wall's angle. False when there is none.
bool ObliqueWallAhead(const std::vector<Reading>& front, const std::vector<Reading>& wide,
                      double axis_rad, double travel_rad, const HallwayFollowerConfig& c,
                      Ahead& ahead) {
  const double step = DegToRad(2.5);
  const auto agreed_ahead = [&](double signed_psi) {
    const double d = AgreedWallDistance(wide, axis_rad + signed_psi, 3, c);
    if (!std::isfinite(d)) return kNoObstacle;
    // It stands ahead: a front sensor reads it (not only the flanks, which also meet a side
    // wall the fit leaves unexplained).
    const bool seen_ahead = std::any_of(front.begin(), front.end(), [&](const Reading& r) {
      return std::abs(ImpliedDistanceIn(r, axis_rad + signed_psi, c) - d) <= c.wall_ahead_spread_in;
    });
    return seen_ahead ? d : kNoObstacle;
  };
  const double max_psi = DegToRad(c.max_oblique_wall_deg) + 1e-9;
  for (double psi = DegToRad(c.min_oblique_wall_deg); psi <= max_psi; psi += step) {
    for (const double sign : {+1.0, -1.0}) {
      if (!std::isfinite(agreed_ahead(sign * psi))) continue;
      double last = psi;
      while (last + step <= max_psi && std::isfinite(agreed_ahead(sign * (last + step)))) {
        last += step;
      }
      const double mid = sign * 0.5 * (psi + last);
      double d = agreed_ahead(mid);
      if (!std::isfinite(d)) d = agreed_ahead(sign * psi);
      // Along the travel direction, the plane at perpendicular distance d lies d / cos.
      ahead.wall_in = d / std::cos(std::abs(WrapPi(axis_rad + mid - travel_rad)));
      ahead.wall_normal_rad = mid;
      return true;
    }
  }
  return false;
}

Ahead LookAhead(const std::vector<SonarRange>& scan, double travel_rad, double heading_error_rad,
                const HallwayEstimate& walls, const HallwayFollowerConfig& c) {
  Ahead ahead;
  const double half_cone = DegToRad(c.cone_deg) / 2.0;
  const double front_half = DegToRad(c.front_half_angle_deg) + 1e-9;
  std::vector<Reading> front, wide;  // unexplained echoes ahead, and within the oblique fan
  for (int k = 0; k < c.sensor_count; ++k) {
    const double bearing = SensorBearingRad(k, c);
    const double off = std::abs(WrapPi(bearing - travel_rad));
    const double r = scan[k].range_in;
    if (!scan[k].valid || off > kPi / 2.0 + 1e-9) continue;
    double side_range = kNoObstacle;
    for (const WallLine* w : {&walls.left, &walls.right}) {
      if (!w->valid) continue;
      side_range =
          std::min(side_range, PredictedWallRangeIn(bearing, w->normal_rad, w->distance_in, c));
    }
    if (r >= side_range - c.side_echo_margin_in) continue;
    if (off > front_half) {
      ahead.free_in = std::min(ahead.free_in, InSweptPathIn(off, r, c));
    }
    if (off > DegToRad(std::max(c.front_half_angle_deg, c.oblique_half_angle_deg)) + 1e-9) {
      continue;
    }
    wide.push_back({bearing, r});
    if (off > front_half) continue;
    front.push_back({bearing, r});
    // The echo may come from anywhere in the cone; the direction nearest the travel axis
    // gives the most cautious along-travel distance.
    ahead.free_in =
        std::min(ahead.free_in, (c.head_radius_in + r) * std::cos(std::max(0.0, off - half_cone)));
  }
  ahead.free_in = std::min(ahead.free_in, SideWallsHeadedIntoIn(walls, travel_rad, c));
  // A wall across the hallway has its normal along the hallway axis.
  const double axis_rad = travel_rad - heading_error_rad;
  ahead.wall_in = AgreedWallDistance(front, axis_rad, 2, c);
  // Only when the front sensors see something that is not across the hallway (at an
  // oblique wall the gate often leaves one of them: the others meet it too steeply).
  if (!std::isfinite(ahead.wall_in) && !front.empty()) {
    ObliqueWallAhead(front, wide, axis_rad, travel_rad, c, ahead);
  }
  return ahead;
}

}  // namespace

const char* ToString(TurnKind kind) {
  switch (kind) {
    case TurnKind::kNone:
      return "none";
    case TurnKind::kCorner:
      return "corner";
    case TurnKind::kJunction:
      return "junction";
    case TurnKind::kHallwayEnd:
      return "hallway_end";
  }
  return "?";
}

double SensorBearingRad(int k, const HallwayFollowerConfig& config) {
  return WrapPi(DegToRad(config.camera_yaw_deg - (k - config.coaxial_sensor) * config.spacing_deg));
}

double PredictedWallRangeIn(double bearing_rad, double normal_rad, double distance_in,
                            const HallwayFollowerConfig& config) {
  const double half_cone = DegToRad(config.cone_deg) / 2.0;
  const double phi = std::abs(WrapPi(bearing_rad - normal_rad));
  const double beyond = std::max(0.0, phi - half_cone);
  if (beyond >= kPi / 2.0) return kNoObstacle;
  const double face_in = distance_in - config.head_radius_in * std::cos(phi);
  if (face_in <= 0.0) return 0.0;
  return face_in / std::cos(beyond);
}

double SideWallsHeadedIntoIn(const HallwayEstimate& walls, double travel_rad,
                             const HallwayFollowerConfig& c) {
  double free_in = kNoObstacle;
  for (const WallLine* w : {&walls.left, &walls.right}) {
    if (!w->valid) continue;
    const double towards = std::cos(WrapPi(w->normal_rad - travel_rad));
    if (towards > std::sin(DegToRad(kHeadedIntoDeg))) {
      free_in = std::min(free_in, std::max(0.0, w->distance_in - c.head_radius_in) / towards);
    }
  }
  return free_in;
}

HallwayEstimate EstimateHallway(const std::vector<SonarRange>& scan,
                                const HallwayFollowerConfig& c) {
  HallwayEstimate est;
  if (static_cast<int>(scan.size()) != c.sensor_count) return est;
  std::vector<Reading> left, right;
  for (int k = 0; k < c.sensor_count; ++k) {
    const SonarRange& s = scan[k];
    if (!s.valid || !std::isfinite(s.range_in) || s.range_in < 0.0) continue;
    ++est.valid_readings;
    const double bearing = SensorBearingRad(k, c);
    const double side = DegToRad(c.side_half_angle_deg) + 1e-9;
    if (std::abs(WrapPi(bearing - kPi / 2.0)) <= side) left.push_back({bearing, s.range_in});
    if (std::abs(WrapPi(bearing + kPi / 2.0)) <= side) right.push_back({bearing, s.range_in});
  }
  // Openness: no echo within range near a side's normal.
  auto open = [&](double normal_rad) {
    for (int k = 0; k < c.sensor_count; ++k) {
      const SonarRange& s = scan[k];
      if (!s.valid || !std::isfinite(s.range_in)) continue;
      const double off = std::abs(WrapPi(SensorBearingRad(k, c) - normal_rad));
      if (off <= DegToRad(c.side_open_half_angle_deg) + 1e-9 &&
          s.range_in + c.head_radius_in <= c.side_open_range_in) {
        return false;
      }
    }
    return true;
  };
  est.left_open = open(kPi / 2.0);
  est.right_open = open(-kPi / 2.0);

  // Grid search over the heading error, from 0 outward so that a flat cost keeps the
  // smallest error.
  const int steps = static_cast<int>(std::floor(c.max_heading_search_deg / c.heading_step_deg));
  double best_cost = std::numeric_limits<double>::infinity();
  double best_psi = 0.0;
  for (int i = 0; i <= 2 * steps; ++i) {
    const int m = (i + 1) / 2 * (i % 2 == 1 ? 1 : -1);
    const double psi = DegToRad(m * c.heading_step_deg);
    const double cost =
        FitSide(left, kPi / 2.0 - psi, c).cost + FitSide(right, -kPi / 2.0 - psi, c).cost;
    if (cost < best_cost - 1e-9) {
      best_cost = cost;
      best_psi = psi;
    }
  }
  const SideFit lf = FitSide(left, kPi / 2.0 - best_psi, c);
  const SideFit rf = FitSide(right, -kPi / 2.0 - best_psi, c);
  auto fill = [](const SideFit& f, double normal_rad, WallLine& w) {
    w.valid = f.inliers > 0;
    w.distance_in = f.distance_in;
    w.normal_rad = WrapPi(normal_rad);
    w.inliers = f.inliers;
    w.outliers = f.outliers;
  };
  fill(lf, kPi / 2.0 - best_psi, est.left);
  fill(rf, -kPi / 2.0 - best_psi, est.right);
  est.heading_valid = lf.inliers + rf.inliers >= 3 && (lf.oblique_inlier || rf.oblique_inlier);
  est.heading_error_rad = est.heading_valid ? best_psi : 0.0;
  if (est.left.valid && est.right.valid) {
    est.offset_valid = true;
    est.lateral_offset_in = (est.right.distance_in - est.left.distance_in) / 2.0;
    est.hallway_width_in = est.right.distance_in + est.left.distance_in;
  }
  const Ahead forward = LookAhead(scan, 0.0, est.heading_error_rad, est, c);
  est.free_forward_in = forward.free_in;
  est.wall_forward_in = forward.wall_in;
  est.wall_forward_normal_rad = forward.wall_normal_rad;
  const Ahead backward = LookAhead(scan, kPi, est.heading_error_rad, est, c);
  est.free_backward_in = backward.free_in;
  est.wall_backward_in = backward.wall_in;
  est.wall_backward_normal_rad = backward.wall_normal_rad;
  return est;
}

std::optional<double> EmptySectorTurnRad(const std::vector<SonarRange>& scan, int travel_sign,
                                         const HallwayFollowerConfig& c) {
  if (static_cast<int>(scan.size()) != c.sensor_count) return std::nullopt;
  const double travel = travel_sign >= 0 ? 0.0 : kPi;
  const double step = DegToRad(c.spacing_deg);
  // The sensor nearest a bearing (relative to the travel direction); -1 if none within half
  // a spacing.
  const auto sensor_at = [&](double rel_rad) {
    for (int k = 0; k < c.sensor_count; ++k) {
      if (std::abs(WrapPi(SensorBearingRad(k, c) - travel - rel_rad)) <= step / 2.0 + 1e-9) return k;
    }
    return -1;
  };
  // No echo, or one from beyond the range that leaves a side open (a far wall down the
  // next stretch, straight along one sensor's axis).
  const auto silent = [&](int k) {
    if (k < 0 || scan[k].outside_footprint) return false;
    return !scan[k].valid || scan[k].range_in + c.head_radius_in > c.side_open_range_in;
  };
  for (const double side : {+1.0, -1.0}) {
    // The run of silent sensors from the first one off the axis outward.
    double last = 0.0;
    for (double b = step; b <= kPi - step / 2.0; b += step) {
      if (!silent(sensor_at(side * b))) break;
      last = b;
    }
    if (last + 1e-9 < DegToRad(c.min_free_sector_deg)) continue;
    // The other side answers (the outer wall of the bend): at least a third of its sensors
    // to abeam. Stopped close in the outer corner of a bend, those that meet its walls at a
    // grazing angle return no echo (a 60 deg bend 27 in off its outer wall: 3 of 6 answer);
    // an open hall leaves them all silent.
    int answering = 0, looked = 0;
    for (double b = step; b <= kPi / 2.0 + 1e-9; b += step) {
      const int k = sensor_at(-side * b);
      if (k < 0) continue;
      ++looked;
      if (scan[k].valid) ++answering;
    }
    if (3 * answering < looked) continue;
    return side * (step + last) / 2.0;
  }
  return std::nullopt;
}

TurnRequest DetectTurn(const HallwayEstimate& estimate, int travel_sign,
                       const HallwayFollowerConfig& config) {
  TurnRequest turn;
  const double wall = travel_sign >= 0 ? estimate.wall_forward_in : estimate.wall_backward_in;
  turn.wall_ahead_in = wall;
  if (!(wall <= config.turn_wall_ahead_in)) return turn;
  const int sign = travel_sign >= 0 ? +1 : -1;
  const double normal = travel_sign >= 0 ? estimate.wall_forward_normal_rad
                                         : estimate.wall_backward_normal_rad;
  if (!(estimate.left_open && estimate.right_open) &&
      std::abs(normal) >= DegToRad(config.min_oblique_wall_deg) - 1e-9) {
    // An oblique wall ahead: the hallway turns away from its normal, by less than a right
    // angle, whether or not the side it turns to reads open yet (at a bend of 45 degrees
    // the inner wall still stands within range abreast of the base).
    turn.kind = TurnKind::kCorner;
    turn.rotate_rad = -std::copysign(kPi / 2.0 - std::abs(normal), normal);
    return turn;
  }
  if (estimate.left_open && estimate.right_open) {
    turn.kind = TurnKind::kJunction;
  } else if (estimate.left_open) {
    turn.kind = TurnKind::kCorner;
    // Travelling forward the base turns CCW toward +y; backward it turns CW so that -x
    // comes round to +y.
    turn.rotate_rad = sign * kPi / 2.0;
  } else if (estimate.right_open) {
    turn.kind = TurnKind::kCorner;
    turn.rotate_rad = -sign * kPi / 2.0;
  } else {
    turn.kind = TurnKind::kHallwayEnd;
  }
  return turn;
}

HallwayFollower::HallwayFollower(HallwayFollowerConfig config) : config_(config) {
  const auto& c = config_;
  auto require = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument("hallway follower: " + what);
  };
  require(c.sensor_count > 0, "sensor_count must be > 0");
  require(c.spacing_deg > 0.0, "spacing_deg must be > 0");
  require(c.head_radius_in >= 0.0, "head_radius_in must be >= 0");
  require(c.cone_deg > 0.0 && c.cone_deg < 180.0, "cone_deg must be in (0, 180)");
  require(c.heading_step_deg > 0.0, "heading_step_deg must be > 0");
  require(c.max_heading_search_deg >= 0.0 && c.max_heading_search_deg < 90.0,
          "max_heading_search_deg must be in [0, 90)");
  require(c.inlier_band_in > 0.0, "inlier_band_in must be > 0");
  require(c.max_speed_ftps > 0.0, "max_speed_ftps must be > 0");
  require(c.max_angular_radps > 0.0, "max_angular_radps must be > 0");
  require(c.max_accel_ftps2 > 0.0, "max_accel_ftps2 must be > 0");
  require(c.brake_decel_ftps2 > 0.0, "brake_decel_ftps2 must be > 0");
  require(c.stop_distance_in >= 0.0, "stop_distance_in must be >= 0");
  require(c.swept_clearance_in >= 0.0, "swept_clearance_in must be >= 0");
  require(c.length_scale_in > 0.0, "length_scale_in must be > 0");
  require(c.damping_ratio > 0.0, "damping_ratio must be > 0");
  require(c.max_correction_heading_deg > 0.0 && c.max_correction_heading_deg < 90.0,
          "max_correction_heading_deg must be in (0, 90)");
}

SteerCommand HallwayFollower::Steer(const HallwayEstimate& estimate, double commanded_speed_ftps,
                                    double dt_s) {
  SteerCommand cmd;
  const auto& c = config_;
  if (!std::isfinite(commanded_speed_ftps) || !std::isfinite(dt_s) || dt_s < 0.0) {
    last_speed_ftps_ = 0.0;
    last_angular_radps_ = 0.0;
    return cmd;
  }
  const double wanted = std::clamp(commanded_speed_ftps, -c.max_speed_ftps, c.max_speed_ftps);
  const int sign = wanted > 0.0 ? +1 : (wanted < 0.0 ? -1 : 0);

  // Speed ramp before an obstacle: the speed from which brake_decel stops at the stop
  // distance.
  double target = 0.0;
  if (sign != 0) {
    const double free_in = sign > 0 ? estimate.free_forward_in : estimate.free_backward_in;
    double allowed_ftps = c.max_speed_ftps;
    if (std::isnan(free_in) || free_in <= c.stop_distance_in) {
      allowed_ftps = 0.0;
      cmd.stopped_for_obstacle = true;
    } else if (std::isfinite(free_in)) {
      const double brake_inps2 = FeetToInches(c.brake_decel_ftps2);
      allowed_ftps = InchesToFeet(std::sqrt(2.0 * brake_inps2 * (free_in - c.stop_distance_in)));
    }
    cmd.limited_by_obstacle = allowed_ftps < std::abs(wanted);
    target = sign * std::min(std::abs(wanted), allowed_ftps);
    cmd.turn = DetectTurn(estimate, sign, c);
  }

  // Speeding up is rate-limited; slowing down and stopping are not. A reversal stops first.
  double speed = target;
  const double last = last_speed_ftps_;
  if (last * target < 0.0) {
    speed = 0.0;
  } else if (std::abs(target) > std::abs(last)) {
    speed = sign * std::min(std::abs(target), std::abs(last) + c.max_accel_ftps2 * dt_s);
  }
  cmd.linear_ftps = speed;
  last_speed_ftps_ = speed;

  // Heading: the scan's when it carries heading information, otherwise the last one
  // carried forward with the turn commanded since (the gate often leaves only readings with
  // the wall normal inside the cone, which say nothing about the heading).
  if (estimate.heading_valid && std::isfinite(estimate.heading_error_rad)) {
    heading_known_ = true;
    heading_rad_ = estimate.heading_error_rad;
  } else if (heading_known_) {
    heading_rad_ += last_angular_radps_ * dt_s;
  }
  last_angular_radps_ = 0.0;

  // Spatial PD (see the header): omega = -|v| b (sin psi - sin psi_ref).
  if (heading_known_ && speed != 0.0) {
    const double a = 1.0 / (c.length_scale_in * c.length_scale_in);
    const double b = 2.0 * c.damping_ratio / c.length_scale_in;
    double sin_ref = 0.0;
    if (estimate.offset_valid && std::isfinite(estimate.lateral_offset_in)) {
      const double cap = std::sin(DegToRad(c.max_correction_heading_deg));
      const double travel_sign = speed > 0.0 ? 1.0 : -1.0;
      sin_ref = std::clamp(-travel_sign * (a / b) * estimate.lateral_offset_in, -cap, cap);
    }
    const double speed_inps = FeetToInches(std::abs(speed));
    const double omega = -speed_inps * b * (std::sin(heading_rad_) - sin_ref);
    cmd.angular_radps = std::clamp(omega, -c.max_angular_radps, c.max_angular_radps);
  }
  last_angular_radps_ = cmd.angular_radps;
  return cmd;
}

}  // namespace stickrep::locomotion
