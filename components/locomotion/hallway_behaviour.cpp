#include "locomotion/hallway_behaviour.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/units.h"

namespace stickrep::locomotion {
namespace {

double WrapPi(double a) { return std::remainder(a, 2.0 * kPi); }

// Below this the base counts as standing still (a turn may start).
constexpr double kAtRestFtps = 0.05;
// A wall across the hallway is also seen by the sensors this far either side of the travel
// direction (outside the three front ones), to within the tolerance below, while something
// narrower (a person, a cart) leaves them reading the side walls farther off: at half the
// width of a 10 ft hallway a 30° sensor's cone meets the wall ahead within 20 in of the axis.
constexpr double kFlankDeg = 30.0;
// Scans in a row that must agree (within kObliqueAgreeRad) on an oblique wall ahead.
constexpr int kObliqueScans = 3;
constexpr double kObliqueAgreeRad = DegToRad(5.0);
constexpr double kFlankToleranceIn = 12.0;
// Once stopped before an obstacle, the base stays put while it is this much farther off.
constexpr double kObstacleHoldIn = 12.0;
// A wall seen nearer than the track puts it by more than this is not a recess.
constexpr double kNearerIn = 2.0;
// Off the axis, the base steers back to it once the front sensors agree on a wall this
// near ahead: the line settles in about 5 length scales (180 in), so the base is back on
// the axis before a corner is read (about 100 in from it) or the base stops before it.
constexpr double kAxisReturnIn = 240.0;

}  // namespace

void HallwayTracker::Predict(double ds_in, double dtheta_rad) {
  if (!initialised_ || !std::isfinite(ds_in) || !std::isfinite(dtheta_rad)) return;
  if (recess_travel_in_ >= 0.0) recess_travel_in_ += std::abs(ds_in);
  const double k = ds_in * std::cos(psi_);
  y_ += ds_in * std::sin(psi_ + dtheta_rad / 2.0);
  psi_ = WrapPi(psi_ + dtheta_rad);
  pyy_ += 2.0 * k * pyp_ + k * k * ppp_;
  pyp_ += k * ppp_;
  const double walk_y = noise_.offset_walk_in_per_sqrt_in;
  const double walk_psi = noise_.heading_walk_rad_per_sqrt_in;
  const double turn = noise_.turn_scale_error * dtheta_rad;
  pyy_ += walk_y * walk_y * std::abs(ds_in);
  ppp_ += walk_psi * walk_psi * std::abs(ds_in) + turn * turn;
}

bool HallwayTracker::Consistent(double offset_in) const {
  if (!std::isfinite(offset_in)) return false;
  if (!initialised_) return true;
  const double v = offset_in - y_;
  const double s = pyy_ + noise_.offset_sigma_in * noise_.offset_sigma_in;
  return v * v <= noise_.gate_sigmas * noise_.gate_sigmas * s;
}

bool HallwayTracker::UpdateOffset(double offset_in, bool recess) {
  if (!std::isfinite(offset_in)) return false;
  const double r = noise_.offset_sigma_in * noise_.offset_sigma_in;
  const double v = offset_in - y_;
  const double s = pyy_ + r;
  bool reinit = !initialised_;
  if (initialised_ && !Consistent(offset_in)) {
    if (recess) {
      if (recess_travel_in_ < 0.0) recess_travel_in_ = 0.0;
      recess_run_.push_back({recess_travel_in_, offset_in});
      if (recess_travel_in_ < noise_.reinit_recess_in && !RecessDrifts()) return false;
    } else if (++rejected_ < noise_.reinit_after) {
      return false;
    }
    reinit = true;
  }
  if (reinit) {
    const double p0 = DegToRad(noise_.initial_heading_sigma_deg);
    if (initialised_) psi_ = 0.0;
    initialised_ = true;
    y_ = offset_in;
    pyy_ = r;
    pyp_ = 0.0;
    ppp_ = p0 * p0;
    rejected_ = 0;
    EndRecessRun();
    return true;
  }
  rejected_ = 0;
  EndRecessRun();
  Correct(1.0, 0.0, v, s);
  return true;
}

bool HallwayTracker::UpdateScan(double offset_in, double heading_rad, bool recess) {
  if (!UpdateOffset(offset_in, recess)) return false;
  UpdateHeading(heading_rad);
  return true;
}

void HallwayTracker::UpdateHeading(double heading_rad) {
  if (!initialised_ || !std::isfinite(heading_rad)) return;
  const double sigma = DegToRad(noise_.heading_sigma_deg);
  const double s = ppp_ + sigma * sigma;
  const double v = WrapPi(heading_rad - psi_);
  if (v * v > noise_.gate_sigmas * noise_.gate_sigmas * s) return;
  Correct(0.0, 1.0, v, s);
}

// The Kalman correction for a measurement h_y y + h_psi psi with innovation v and innovation
// variance s: x += P H' v / s, P -= P H' H P / s.
void HallwayTracker::Correct(double h_y, double h_psi, double v, double s) {
  const double py = pyy_ * h_y + pyp_ * h_psi;  // P H'
  const double pp = pyp_ * h_y + ppp_ * h_psi;
  y_ += py / s * v;
  psi_ = WrapPi(psi_ + pp / s * v);
  pyy_ -= py * py / s;
  pyp_ -= py * pp / s;
  ppp_ -= pp * pp / s;
}

void HallwayTracker::TurnedOnto(double rad) {
  if (!initialised_) return;
  psi_ = WrapPi(psi_ - rad);
  // The offset in the new hallway is anyone's guess until its walls are fitted.
  pyy_ = 1e4;
  pyp_ = 0.0;
  rejected_ = 0;
  EndRecessRun();
}

bool HallwayTracker::RecessDrifts() const {
  const double window = noise_.recess_window_in;
  if (window <= 0.0 || recess_travel_in_ < 2.0 * window) return false;
  // Least-squares slope of offset over travel across the window.
  double n = 0.0, st = 0.0, so = 0.0, stt = 0.0, sto = 0.0;
  for (const RecessSample& s : recess_run_) {
    if (s.travel_in < recess_travel_in_ - window) continue;
    n += 1.0;
    st += s.travel_in;
    so += s.offset_in;
    stt += s.travel_in * s.travel_in;
    sto += s.travel_in * s.offset_in;
  }
  const double spread = n * stt - st * st;
  if (n < 4.0 || spread <= 0.25 * window * window * n * n / 12.0) return false;  // too few
  const double slope = (n * sto - st * so) / spread;
  return std::abs(slope) > std::tan(DegToRad(noise_.recess_max_slope_deg));
}

bool HallwayTracker::offset_known() const {
  return initialised_ && std::sqrt(pyy_) <= noise_.known_offset_sigma_in;
}

bool HallwayTracker::heading_known() const {
  return initialised_ && std::sqrt(ppp_) <= DegToRad(noise_.known_heading_sigma_deg);
}

bool HallwayBehaviour::WallSpansHallway(double wall_in, double wall_normal_rad) const {
  const HallwayFollowerConfig& c = config_.follower;
  if (static_cast<int>(scan_.size()) != c.sensor_count) return false;
  const double travel_rad = travel_sign_ > 0 ? 0.0 : kPi;
  const double heading = tracker_.heading_known() ? tracker_.heading_rad() : 0.0;
  // The wall ahead faces back along the axis, or turned by its oblique angle; its
  // perpendicular distance is the along-travel one foreshortened.
  const double normal_rad = travel_rad - heading + wall_normal_rad;
  wall_in *= std::cos(wall_normal_rad);
  int seen = 0;
  for (int side : {+1, -1}) {
    // The sensor nearest kFlankDeg off the travel direction on this side.
    int best = -1;
    double best_off = kPi;
    for (int k = 0; k < c.sensor_count; ++k) {
      const double off =
          std::abs(WrapPi(SensorBearingRad(k, c) - (travel_rad + side * DegToRad(kFlankDeg))));
      if (off < best_off) best_off = off, best = k;
    }
    // An echo outside the footprint is rough but shows where something is: a wall ahead
    // meets the flank sensors at a steep incidence, so the gate often sets them aside.
    if (!scan_[best].valid && !scan_[best].outside_footprint) continue;  // no say either way
    const double predicted = PredictedWallRangeIn(SensorBearingRad(best, c), normal_rad, wall_in, c);
    if (!std::isfinite(predicted)) continue;
    const double r = scan_[best].range_in;
    if (r > predicted + kFlankToleranceIn) return false;  // it sees past: the side wall
    if (r >= predicted - kFlankToleranceIn) ++seen;
  }
  return seen > 0;
}

const char* ToString(BehaviourState state) {
  switch (state) {
    case BehaviourState::kNoScan:
      return "no_scan";
    case BehaviourState::kFollowing:
      return "following";
    case BehaviourState::kStopping:
      return "stopping";
    case BehaviourState::kTurning:
      return "turning";
    case BehaviourState::kObstacle:
      return "obstacle";
  }
  return "?";
}

double ViewPacedSpeedFtps(const HallwayBehaviourConfig& c, double range_in) {
  if (c.frames_per_door <= 0 || !std::isfinite(range_in)) return kNoObstacle;
  const double view_in = 2.0 * std::max(0.0, range_in) * std::tan(DegToRad(c.camera_fov_deg) / 2.0);
  const double margin_in = std::max(0.0, view_in - c.door_in_view_in);
  return std::max(c.min_view_speed_ftps,
                  InchesToFeet(margin_in / (c.frames_per_door * c.camera_frame_period_s)));
}

double ViewOffsetIn(const HallwayBehaviourConfig& c, double width_in) {
  if (c.frames_per_door <= 0 || c.max_view_offset_in <= 0.0 || !std::isfinite(width_in)) return 0.0;
  // The range at which the widest door stays in view for the set frames at top speed.
  const double top_inps = FeetToInches(c.follower.max_speed_ftps);
  const double range_in =
      (c.door_in_view_in + c.frames_per_door * c.camera_frame_period_s * top_inps) /
      (2.0 * std::tan(DegToRad(c.camera_fov_deg) / 2.0));
  const double room_in = width_in / 2.0 - c.follower.stop_distance_in;
  return -std::clamp(range_in - width_in / 2.0, 0.0,
                     std::max(0.0, std::min(c.max_view_offset_in, room_in)));
}

HallwayBehaviour::HallwayBehaviour(HallwayBehaviourConfig config)
    : config_(config), follower_(config.follower) {
  const auto& c = config_;
  auto require = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument("hallway behaviour: " + what);
  };
  require(c.turn_rate_radps > 0.0, "turn_rate_radps must be > 0");
  require(c.turn_accel_radps2 > 0.0, "turn_accel_radps2 must be > 0");
  require(c.turn_tolerance_deg > 0.0 && c.turn_tolerance_deg < 45.0,
          "turn_tolerance_deg must be in (0, 45)");
  require(c.scan_timeout_s > 0.0, "scan_timeout_s must be > 0");
  require(c.wall_memory_s >= 0.0, "wall_memory_s must be >= 0");
  require(c.obstacle_patience_s > 0.0, "obstacle_patience_s must be > 0");
  require(c.stop_tolerance_in > 0.0, "stop_tolerance_in must be > 0");
  require(c.default_hallway_width_in > 0.0, "default_hallway_width_in must be > 0");
  require(c.envelope_offset_in > 0.0 && c.envelope_heading_deg > 0.0,
          "the envelope must be > 0");
  require(c.frames_per_door >= 0, "frames_per_door must be >= 0");
  require(c.max_view_offset_in >= 0.0 && c.max_view_offset_in < c.envelope_offset_in,
          "max_view_offset_in must be in [0, envelope_offset_in)");
  require(c.view_offset_after_in >= 0.0, "view_offset_after_in must be >= 0");
  require(c.camera_fov_deg > 0.0 && c.camera_fov_deg < 180.0, "camera_fov_deg must be in (0, 180)");
  require(c.camera_frame_period_s > 0.0, "camera_frame_period_s must be > 0");
  require(c.door_in_view_in >= 0.0 && c.min_view_speed_ftps > 0.0,
          "door_in_view_in must be >= 0 and min_view_speed_ftps > 0");
  require(c.stall_speed_ftps > 0.0 && c.stall_time_s > 0.0 && c.stall_travel_in > 0.0 &&
              c.stall_travel_in < FeetToInches(c.stall_speed_ftps) * c.stall_time_s,
          "stall_speed_ftps, stall_time_s and stall_travel_in must be > 0, and stall_travel_in "
          "less than stall_time_s at stall_speed_ftps");
}

void HallwayBehaviour::Reset() {
  state_ = have_scan_ ? BehaviourState::kFollowing : BehaviourState::kNoScan;
  follower_.Reset();
  commanded_sign_ = 0;
  travel_sign_ = +1;
  last_linear_ftps_ = 0.0;
  last_angular_radps_ = 0.0;
  driven_ = false;
  wall_known_ = false;
  oblique_scans_ = 0;
  pending_ = TurnKind::kNone;
  squaring_ = false;
  squared_ = false;
  pending_rotate_rad_ = 0.0;
  blocked_ = false;
}

void HallwayBehaviour::OnScan(const std::vector<SonarRange>& scan, double now_s) {
  estimate_ = EstimateHallway(scan, config_.follower);
  scan_ = scan;
  have_scan_ = true;
  scan_fresh_ = true;
  scan_time_s_ = now_s;
  if (state_ == BehaviourState::kTurning) return;  // the walls are sideways mid-turn
  const double wall = travel_sign_ > 0 ? estimate_.wall_forward_in : estimate_.wall_backward_in;
  // The width is taken on a plain stretch only: near the end of a hallway a side that opens
  // leaves the fit with stray echoes from round the corner; in an open hall one reading
  // within side_open_range_in (a column, a corner seen edge-on) keeps a side "closed" while
  // its fitted line lies across the hall, so both lines must lie within that range too.
  const double side_range = config_.follower.side_open_range_in;
  if (!wall_known_ && !std::isfinite(wall) && !estimate_.left_open && !estimate_.right_open &&
      estimate_.offset_valid && estimate_.left.inliers >= 2 && estimate_.right.inliers >= 2 &&
      estimate_.left.distance_in <= side_range && estimate_.right.distance_in <= side_range &&
      estimate_.hallway_width_in > 2.0 * config_.follower.stop_distance_in) {
    hallway_width_in_ = estimate_.hallway_width_in;
    NoteWidth(hallway_width_in_);
  }
  if (!std::isfinite(wall)) {
    oblique_scans_ = 0;
    return;
  }
  // An oblique wall is believed once kObliqueScans scans in a row agree on its angle; one
  // scan's is as likely a crossing's corner seen edge-on, or an open door's leaf. Until
  // then the wall ahead stays as it was.
  const double normal =
      travel_sign_ > 0 ? estimate_.wall_forward_normal_rad : estimate_.wall_backward_normal_rad;
  if (normal == 0.0) {
    oblique_scans_ = 0;
  } else if (oblique_scans_ > 0 && std::abs(normal - oblique_normal_rad_) <= kObliqueAgreeRad) {
    ++oblique_scans_;
  } else {
    oblique_scans_ = 1;
  }
  oblique_normal_rad_ = normal;
  if (normal != 0.0 && oblique_scans_ < kObliqueScans) return;
  wall_known_ = true;
  wall_ahead_in_ = wall;
  wall_normal_rad_ = normal;
  wall_odometer_in_ = previous_odometer_in_;
  wall_time_s_ = now_s;
}

void HallwayBehaviour::NoteWidth(double width_in) {
  const bool narrow = ViewOffsetIn(config_, width_in) != 0.0;
  while (!narrow_widths_.empty() &&
         narrow_widths_.front().first < travel_in_ - config_.view_offset_after_in) {
    narrow_widths_.pop_front();
  }
  if (narrow) narrow_widths_.emplace_back(travel_in_, width_in);
  if (!narrow_widths_.empty()) {
    least_narrow_width_in_ = narrow_widths_.front().second;
    for (const auto& [travel_in, w] : narrow_widths_) {
      least_narrow_width_in_ = std::min(least_narrow_width_in_, w);
    }
  }
  if (narrow == narrow_) {
    narrow_disagree_since_in_ = -1.0;
    return;
  }
  if (narrow_disagree_since_in_ < 0.0) narrow_disagree_since_in_ = travel_in_;
  if (travel_in_ - narrow_disagree_since_in_ >= config_.view_offset_after_in) {
    narrow_ = narrow;
    narrow_disagree_since_in_ = -1.0;
  }
}

void HallwayBehaviour::Report(BehaviourOutput& out) const {
  out.state = state_;
  out.travel_sign = travel_sign_;
  out.offset_valid = tracker_.offset_known();
  out.lateral_offset_in = out.offset_valid ? tracker_.offset_in() : 0.0;
  out.target_offset_in = target_offset_in_;
  out.heading_valid = tracker_.heading_known();
  out.heading_error_rad = out.heading_valid ? tracker_.heading_rad() : 0.0;
  out.in_envelope =
      state_ == BehaviourState::kFollowing && out.offset_valid &&
      std::abs(out.lateral_offset_in - target_offset_in_) <= config_.envelope_offset_in &&
      out.heading_valid &&
      std::abs(out.heading_error_rad) <= DegToRad(config_.envelope_heading_deg);
}

bool HallwayBehaviour::NotNearer(const WallLine& wall, int side, double half_width_in) const {
  // The track puts the left (+1) wall at half - y, the right (-1) at half + y.
  return wall.distance_in >= half_width_in - side * tracker_.offset_in() - kNearerIn;
}

void HallwayBehaviour::TrackBothWalls(double width_in) {
  // Both walls give the offset and the heading. Where one of them is set back (a door, an
  // alcove) or stands out (a pilaster), the scan's offset is an outlier and its heading is
  // fitted to the same wrong wall; the other wall alone, with the width, still places the
  // base. A wall neither explains restarts the track only as HallwayTracker says, and then
  // from the scan's heading too: round a bend the new stretch's walls are such walls.
  const double half = width_in / 2.0;
  const WallLine& l = estimate_.left;
  const WallLine& r = estimate_.right;
  // One wall alone places the base only on a known track and a measured width.
  const bool single = tracker_.offset_known() && hallway_width_in_ > 0.0;
  const bool l_ok = single && l.valid && l.inliers >= 2;
  const bool r_ok = single && r.valid && r.inliers >= 2;
  const double heading = estimate_.heading_valid ? estimate_.heading_error_rad
                                                 : std::numeric_limits<double>::quiet_NaN();
  if (estimate_.offset_valid && tracker_.Consistent(estimate_.lateral_offset_in)) {
    tracker_.UpdateScan(estimate_.lateral_offset_in, heading);
    return;
  }
  if (l_ok && tracker_.Consistent(half - l.distance_in)) {
    tracker_.UpdateOffset(half - l.distance_in);
    return;
  }
  if (r_ok && tracker_.Consistent(r.distance_in - half)) {
    tracker_.UpdateOffset(r.distance_in - half);
    return;
  }
  if (!estimate_.offset_valid) return;
  const bool recess = (!l_ok || NotNearer(l, +1, half)) && (!r_ok || NotNearer(r, -1, half));
  tracker_.UpdateScan(estimate_.lateral_offset_in, heading, recess);
}

bool HallwayBehaviour::TurnInPlace(double odometry_heading_rad, double dt_s, BehaviourOutput& out) {
  const double remaining = WrapPi(turn_target_rad_ - odometry_heading_rad);
  const double a = config_.turn_accel_radps2;
  const bool settled = std::abs(remaining) <= DegToRad(config_.turn_tolerance_deg) &&
                       std::abs(last_angular_radps_) <= a * dt_s + 1e-12;
  if (!settled) {
    // The rate that still brakes to rest at the target, within the ramp either way.
    const double wanted = std::copysign(
        std::min(config_.turn_rate_radps, std::sqrt(2.0 * a * std::abs(remaining))), remaining);
    out.angular_radps =
        std::clamp(wanted, last_angular_radps_ - a * dt_s, last_angular_radps_ + a * dt_s);
    last_angular_radps_ = out.angular_radps;
    last_linear_ftps_ = 0.0;
    out.reason = fmt::format(
        "turning {:+.0f} deg in place {}: {:.0f} deg to go", RadToDeg(turn_rad_),
        squaring_ ? "to square up to the hallway" : fmt::format("at a {}", ToString(pending_)),
        RadToDeg(std::abs(remaining)));
    Report(out);
    return true;
  }
  // Done: follow the new hallway with a fresh controller and no stale wall. Squared up in
  // the same hallway, the track starts again from the next scan: its heading was the one
  // that led into the wall.
  if (squaring_) {
    tracker_.Reset();
  } else {
    tracker_.TurnedOnto(turn_rad_);
  }
  squaring_ = false;
  state_ = BehaviourState::kFollowing;
  pending_ = TurnKind::kNone;
  follower_.Reset();
  wall_known_ = false;
  last_angular_radps_ = 0.0;
  return false;
}

void HallwayBehaviour::Reverse(BehaviourOutput& out) {
  travel_sign_ = -travel_sign_;
  wall_known_ = false;
  blocked_ = false;
  follower_.Reset();
  last_linear_ftps_ = last_angular_radps_ = 0.0;
  state_ = BehaviourState::kFollowing;
  pending_ = TurnKind::kNone;
  squaring_ = false;
  out.linear_ftps = out.angular_radps = 0.0;
  out.reversed = true;
  out.turn_kind = TurnKind::kHallwayEnd;
}

bool HallwayBehaviour::Stalled(double odometer_in, double now_s, BehaviourOutput& out) {
  // The speed last asked of the base is what it has been driving at since.
  if (std::abs(last_linear_ftps_) < config_.stall_speed_ftps) {
    driven_ = false;
    return false;
  }
  if (!driven_ || std::abs(odometer_in - driven_odometer_in_) >= config_.stall_travel_in) {
    driven_ = true;
    driven_since_s_ = now_s;
    driven_odometer_in_ = odometer_in;
    return false;
  }
  const double driven_s = now_s - driven_since_s_;
  if (driven_s < config_.stall_time_s) return false;
  const double moved_in = std::abs(odometer_in - driven_odometer_in_);
  const double speed_ftps = std::abs(last_linear_ftps_);
  driven_ = false;
  Reverse(out);
  out.stalled = true;
  out.reason = fmt::format(
      "stalled: driven at {:.1f} ft/s for {:.1f} s, the base moved {:.1f} in (against something "
      "the sonar does not see): travel reversed, now {}",
      speed_ftps, driven_s, moved_in, travel_sign_ > 0 ? "forward" : "backward");
  Report(out);
  return true;
}

bool HallwayBehaviour::BrakeAndAct(double wall_in, double odometry_heading_rad, double dt_s,
                                   BehaviourOutput& out) {
  const double speed =
      std::max(0.0, std::abs(last_linear_ftps_) - config_.follower.brake_decel_ftps2 * dt_s);
  if (speed > kAtRestFtps) {
    out.linear_ftps = travel_sign_ * speed;
    last_linear_ftps_ = out.linear_ftps;
    last_angular_radps_ = 0.0;
    out.reason = fmt::format("{} ahead: braking before acting on it", ToString(pending_));
    Report(out);
    return true;
  }
  last_linear_ftps_ = 0.0;
  follower_.Reset();
  if (pending_ == TurnKind::kHallwayEnd) {
    Reverse(out);
    out.reason = fmt::format("hallway end {:.0f} in ahead: travel reversed, now {}", wall_in,
                             travel_sign_ > 0 ? "forward" : "backward");
    Report(out);
    return true;
  }
  state_ = BehaviourState::kTurning;
  turn_rad_ = pending_rotate_rad_;
  // Turn onto the new hallway's direction, not by a fixed angle from wherever the base
  // points: a heading error left from aligning is taken out in the same turn.
  const double heading_error = tracker_.heading_known() ? tracker_.heading_rad() : 0.0;
  turn_target_rad_ = WrapPi(odometry_heading_rad - heading_error + pending_rotate_rad_);
  last_angular_radps_ = 0.0;
  out.turn_started = true;
  blocked_ = false;
  out.turn_kind = pending_;
  // A turn decided on an opened side alone may have no wall sensed ahead to give a distance.
  const std::string ahead = std::isfinite(wall_in) ? fmt::format("{:.0f} in ahead", wall_in)
                                                   : std::string("ahead, no wall sensed");
  out.reason = fmt::format("{} {}: turning {:+.0f} deg in place", ToString(pending_), ahead,
                           RadToDeg(pending_rotate_rad_));
  Report(out);
  return true;
}

void HallwayBehaviour::UpdateTrack(double width_in) {
  // The scan's fit feeds the tracker where both walls are plain. Where one side has opened
  // (a crossing, the hallway just turned out of) the other wall alone places the base,
  // with the width measured before; its stray echoes from round the corner make the heading
  // untrustworthy there.
  if (!estimate_.left_open && !estimate_.right_open) {
    TrackBothWalls(width_in);
    return;
  }
  if (estimate_.left_open == estimate_.right_open) return;
  // Before any width was measured (a start beside an open hall) the default width places
  // the base: a guess, but one that keeps it off the wall it can see.
  const WallLine& plain = estimate_.left_open ? estimate_.right : estimate_.left;
  if (!plain.valid || plain.inliers < 2) return;
  const double half = width_in / 2.0;
  const double offset = estimate_.left_open ? plain.distance_in - half : half - plain.distance_in;
  // The wall seen farther than the track puts it: a recess in it.
  const bool accepted =
      tracker_.UpdateOffset(offset, NotNearer(plain, estimate_.left_open ? -1 : +1, half));
  // With no heading yet, the one wall's is the best there is; otherwise odometry carries it
  // (stray echoes from round a corner bias a one-sided fit).
  if (accepted && !tracker_.heading_known() && estimate_.heading_valid) {
    tracker_.UpdateHeading(estimate_.heading_error_rad);
  }
}

void HallwayBehaviour::Blocked(double odometer_in, double now_s, BehaviourOutput& out) {
  // One blocked spell lasts until the base has got on by kObstacleHoldIn: a wall met at an
  // angle (a bend's outer corner, an opening's edge, met with no wall to steer by) clears
  // for a scan now and then as the base creeps at it, and must not restart the patience
  // each time. Blocked for obstacle_patience_s, the way ahead is taken for closed and
  // travel reverses (§6.3 A4), as at a hallway end.
  const double free_in = travel_sign_ > 0 ? estimate_.free_forward_in : estimate_.free_backward_in;
  const char* where = travel_sign_ > 0 ? "ahead" : "behind";
  if (!blocked_ && SquareUp(free_in, out)) return;
  if (!blocked_) {
    blocked_ = true;
    blocked_since_s_ = now_s;
    blocked_odometer_in_ = odometer_in;
  } else if (now_s - blocked_since_s_ >= config_.obstacle_patience_s) {
    Reverse(out);
    out.reason = fmt::format("blocked {:.0f} s by something {:.0f} in {}: travel reversed, now {}",
                             config_.obstacle_patience_s, free_in, where,
                             travel_sign_ > 0 ? "forward" : "backward");
    return;
  }
  out.reason = fmt::format("obstacle {:.0f} in {}: stopped until it clears", free_in, where);
}

bool HallwayBehaviour::SquareUp(double free_in, BehaviourOutput& out) {
  // Stopped by a side wall the base heads into (a hallway that bends where the other side
  // is open, so nothing showed the bend but this wall; a start turned far from the axis):
  // that wall gives the hallway's direction, and the base turns in place onto it rather than
  // wait before a wall that will not move. Its speed was zero, so steering could not.
  // Once per kObstacleHoldIn of travel: squared up and stopped again at once, the fit is
  // not to be trusted, and the base waits and then reverses as before any obstacle.
  const HallwayFollowerConfig& fc = config_.follower;
  const double side_in = SideWallsHeadedIntoIn(estimate_, travel_sign_ > 0 ? 0.0 : kPi, fc);
  if (!estimate_.heading_valid || !std::isfinite(side_in) || side_in > free_in + 1e-6) return false;
  if (squared_ && std::abs(previous_odometer_in_ - squared_odometer_in_) < kObstacleHoldIn) {
    return false;
  }
  squared_ = true;
  squared_odometer_in_ = previous_odometer_in_;
  state_ = BehaviourState::kTurning;
  pending_ = TurnKind::kNone;
  squaring_ = true;
  turn_rad_ = -estimate_.heading_error_rad;
  turn_target_rad_ = WrapPi(previous_heading_rad_ + turn_rad_);
  last_angular_radps_ = 0.0;
  out.turn_started = true;
  out.reason = fmt::format(
      "headed {:+.0f} deg into the wall {:.0f} in {}: squaring up to it in place",
      RadToDeg(estimate_.heading_error_rad), side_in, travel_sign_ > 0 ? "ahead" : "behind");
  return true;
}

bool HallwayBehaviour::ActAtWall(double wall_in, double wall_normal, double stop_at_in,
                                 bool was_obstacle, double now_s, BehaviourOutput& out) {
  const HallwayFollowerConfig& fc = config_.follower;
  HallwayEstimate seen = estimate_;
  (travel_sign_ > 0 ? seen.wall_forward_in : seen.wall_backward_in) = wall_in;
  (travel_sign_ > 0 ? seen.wall_forward_normal_rad : seen.wall_backward_normal_rad) = wall_normal;
  HallwayFollowerConfig at = fc;
  at.turn_wall_ahead_in = std::max(fc.turn_wall_ahead_in, stop_at_in + 2.0 * config_.stop_tolerance_in);
  TurnRequest turn = DetectTurn(seen, travel_sign_, at);
  if (turn.kind == TurnKind::kHallwayEnd) {
    if (const auto rotate = EmptySectorTurnRad(scan_, travel_sign_, fc)) {
      turn.kind = TurnKind::kCorner;
      turn.rotate_rad = *rotate;
    }
  }
  // Something that has stood in the way, unmoved, for obstacle_patience_s is taken for what
  // the sides say it is (the flank check leans on the heading estimate, which can be off
  // right after aligning): a corner to turn, or the end of the way to reverse from.
  if (!was_obstacle) obstacle_since_s_ = now_s;
  const bool patience_over = was_obstacle && now_s - obstacle_since_s_ >= config_.obstacle_patience_s;
  if (turn.kind != TurnKind::kNone && !patience_over && !WallSpansHallway(wall_in, wall_normal)) {
    // Something in the way, not the end of the hallway: wait here until it goes.
    out.obstacle_stop_started = !was_obstacle;
    state_ = BehaviourState::kObstacle;
    follower_.Reset();
    last_linear_ftps_ = last_angular_radps_ = 0.0;
    out.reason = fmt::format("obstacle {:.0f} in {} narrower than the hallway: stopped until it "
                             "clears",
                             wall_in, travel_sign_ > 0 ? "ahead" : "behind");
    Report(out);
    return true;
  }
  if (turn.kind != TurnKind::kNone) {
    pending_ = turn.kind;
    // A junction: turn toward the camera side, where the mapped wall is.
    pending_rotate_rad_ = turn.kind == TurnKind::kJunction ? travel_sign_ * kPi / 2.0 : turn.rotate_rad;
    state_ = BehaviourState::kStopping;
    out.turn_kind = turn.kind;
  }
  return false;
}

void HallwayBehaviour::Follow(double speed, double width_in, double wall_in, double stop_at_in,
                              bool was_obstacle, double odometer_in, double now_s, double dt_s,
                              BehaviourOutput& out) {
  // Following: the mission's speed, capped so the base stops on the new hallway's axis.
  const HallwayFollowerConfig& fc = config_.follower;
  if (std::isfinite(wall_in)) {
    const double margin_in = std::max(0.0, wall_in - stop_at_in);
    speed = std::min(speed, InchesToFeet(std::sqrt(2.0 * FeetToInches(fc.brake_decel_ftps2) * margin_in)));
  }
  // Paced for the camera at the mapped wall's range: half the hallway, less the offset
  // toward it (the tracked offset, not one scan's, which a door recess lengthens).
  speed = std::min(speed, ViewPacedSpeedFtps(config_, width_in / 2.0 -
                                                          (tracker_.offset_known() ? tracker_.offset_in() : 0.0)));
  // Where a wall ahead reaches into the side sensors' view, odometry carries the track.
  if (scan_fresh_ && !std::isfinite(wall_in)) UpdateTrack(width_in);
  scan_fresh_ = false;
  // Steered to the line the camera wants: the axis, or off it in a narrow hallway. With a
  // wall the scan shows within kAxisReturnIn ahead, or a wall ahead believed (a corner, a
  // hallway end), back to the axis: the corner is read, and the base stops, from there.
  target_offset_in_ = 0.0;
  const double wall_seen_in =
      travel_sign_ > 0 ? estimate_.wall_forward_in : estimate_.wall_backward_in;
  if (narrow_ && !narrow_widths_.empty() && !std::isfinite(wall_in) &&
      !(wall_seen_in < kAxisReturnIn)) {
    target_offset_in_ = ViewOffsetIn(config_, least_narrow_width_in_);
  }
  HallwayEstimate steer_on = estimate_;
  steer_on.offset_valid = tracker_.offset_known();
  steer_on.lateral_offset_in = tracker_.offset_in() - target_offset_in_;
  steer_on.heading_valid = tracker_.heading_known();
  steer_on.heading_error_rad = tracker_.heading_rad();
  const SteerCommand cmd = follower_.Steer(steer_on, travel_sign_ * speed, dt_s);
  out.linear_ftps = cmd.linear_ftps;
  out.angular_radps = cmd.angular_radps;
  last_linear_ftps_ = cmd.linear_ftps;
  last_angular_radps_ = cmd.angular_radps;
  if (cmd.stopped_for_obstacle) {
    out.obstacle_stop_started = !was_obstacle;
    state_ = BehaviourState::kObstacle;
    Blocked(odometer_in, now_s, out);
  } else {
    if (blocked_ && std::abs(odometer_in - blocked_odometer_in_) > kObstacleHoldIn) blocked_ = false;
    state_ = BehaviourState::kFollowing;
    if (std::isfinite(wall_in)) {
      out.reason = fmt::format("following; wall {:.0f} in ahead, slowing to stop {:.0f} in from it",
                               wall_in, stop_at_in);
    } else {
      out.reason = "following the hallway";
    }
  }
  Report(out);
}

BehaviourOutput HallwayBehaviour::Step(double commanded_speed_ftps, double odometry_heading_rad,
                                       double odometer_in, double now_s, double dt_s) {
  BehaviourOutput out;
  const HallwayFollowerConfig& fc = config_.follower;
  if (!std::isfinite(commanded_speed_ftps) || !std::isfinite(odometry_heading_rad) ||
      !std::isfinite(odometer_in) || !std::isfinite(now_s) || !std::isfinite(dt_s) ||
      dt_s < 0.0) {
    follower_.Reset();
    last_linear_ftps_ = last_angular_radps_ = 0.0;
    out.reason = "non-finite speed, odometry or time: holding the base";
    Report(out);
    return out;
  }
  if (have_odometer_) {
    tracker_.Predict(odometer_in - previous_odometer_in_,
                     WrapPi(odometry_heading_rad - previous_heading_rad_));
    travel_in_ += std::abs(odometer_in - previous_odometer_in_);
  }
  have_odometer_ = true;
  previous_odometer_in_ = odometer_in;
  previous_heading_rad_ = odometry_heading_rad;
  if (Stalled(odometer_in, now_s, out)) return out;
  const int sign = commanded_speed_ftps > 0.0 ? +1 : (commanded_speed_ftps < 0.0 ? -1 : 0);
  if (sign != 0 && sign != commanded_sign_) {
    // The mission chose a direction: it holds until the mission changes it again or a
    // hallway end reverses it.
    commanded_sign_ = sign;
    if (sign != travel_sign_) wall_known_ = false;
    travel_sign_ = sign;
  }

  // Rotating in place needs odometry only.
  if (state_ == BehaviourState::kTurning && TurnInPlace(odometry_heading_rad, dt_s, out)) return out;

  if (!have_scan_ || now_s - scan_time_s_ > config_.scan_timeout_s) {
    state_ = BehaviourState::kNoScan;
    follower_.Reset();
    last_linear_ftps_ = last_angular_radps_ = 0.0;
    out.reason = have_scan_ ? fmt::format("no sonar scan for {:.1f} s: holding the base",
                                          now_s - scan_time_s_)
                            : "waiting for the first sonar scan: holding the base";
    Report(out);
    return out;
  }
  if (state_ == BehaviourState::kNoScan) state_ = BehaviourState::kFollowing;

  // The wall across the hallway ahead, dead-reckoned from the scan that saw it.
  const double width_in = hallway_width_in_ > 0.0 ? hallway_width_in_ : config_.default_hallway_width_in;
  if (wall_known_ && now_s - wall_time_s_ > config_.wall_memory_s) wall_known_ = false;
  // Stop on the axis of the hallway ahead: half its width from the wall ahead, measured
  // square to that wall (along the travel direction, farther for an oblique one).
  const double wall_normal = wall_known_ ? wall_normal_rad_ : 0.0;
  const double stop_at_in = std::max(width_in / 2.0, fc.stop_distance_in) / std::cos(wall_normal);
  double wall_in = kNoObstacle;
  if (wall_known_) wall_in = wall_ahead_in_ - travel_sign_ * (odometer_in - wall_odometer_in_);

  // At the stopping point (or braking to it) decide what the wall ahead means.
  const bool was_obstacle = state_ == BehaviourState::kObstacle;
  if (was_obstacle) state_ = BehaviourState::kFollowing;
  // Waiting before an obstacle holds until it has gone (no creeping up to it by the
  // tolerance, scan by scan).
  const double hold_in = was_obstacle ? kObstacleHoldIn : 0.0;
  if (state_ == BehaviourState::kFollowing &&
      wall_in - stop_at_in <= config_.stop_tolerance_in + hold_in &&
      ActAtWall(wall_in, wall_normal, stop_at_in, was_obstacle, now_s, out)) {
    return out;
  }

  if (state_ == BehaviourState::kStopping && BrakeAndAct(wall_in, odometry_heading_rad, dt_s, out)) {
    return out;
  }

  Follow(std::abs(commanded_speed_ftps), width_in, wall_in, stop_at_in, was_obstacle, odometer_in,
         now_s, dt_s, out);
  return out;
}

}  // namespace stickrep::locomotion
