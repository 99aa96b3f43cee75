#include "virtual_robot/virtual_robot_component.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "common/units.h"

namespace stickrep::virtual_robot {

namespace {

// The navigation envelope (§6.4.2) is judged away from corners, where the robot turns
// instead of following (8 ft), and once the robot has had room to align from its start
// (20 ft travelled).
constexpr double kEnvelopeCornerDistanceIn = 96.0;
constexpr double kEnvelopeSettleDistanceIn = 240.0;
// Wheel speeds below this are a base at rest.
constexpr double kAtRestFtps = 0.01;
// The true path is kept as a point every this many inches.
constexpr double kPathSpacingIn = 3.0;

}  // namespace

std::string Describe(const PoseCheck& c) {
  return fmt::format(
      "pose recovered after {} edges, {:.1f} ft, {:.1f} s simulated: ring '{}' edge {} {}; truth "
      "ring '{}' edge {} {}: {}",
      c.edges_sensed, c.distance_ft, c.time_s, c.ring_id, c.edge,
      c.forward ? "forward" : "backward", c.truth_ring_id, c.truth_edge,
      c.truth_forward ? "forward" : "backward", c.correct ? "CORRECT" : "INCORRECT");
}

VirtualRobotComponent::VirtualRobotComponent(component::Context& ctx,
                                             const VirtualRobotConfig& config,
                                             std::unique_ptr<WorldSim> sim, Outputs out)
    : ctx_(ctx), config_(config), sim_(std::move(sim)), out_(out) {
  const SimTruth t = sim_->Truth();
  start_ = fmt::format(
      "ring '{}' edge {} + {:.1f} in, {:+.1f} in off the axis, heading {:+.1f} deg (seed {})",
      sim_->ring_id(), t.edge_index, t.offset_in, t.lateral_offset_in,
      RadToDeg(t.heading_error_rad), config_.seed);
  path_.push_back({t.X_WR.x_in, t.X_WR.y_in});
  markers_.push_back({t.X_WR.x_in, t.X_WR.y_in, "start"});
}

std::vector<component::Timer> VirtualRobotComponent::Timers() {
  // The world steps first at each instant it is due, so every device reads the world as the
  // last step left it.
  return {{1.0 / config_.sim_rate_hz, [this] { Step(); }},
          {1.0 / config_.encoder_rate_hz, [this] { PublishEncodersAndTruth(); }},
          {1.0 / config_.sonar_rate_hz, [this] { PublishEcho(); }},
          {1.0 / config_.camera_rate_hz, [this] { PublishFrame(); }}};
}

void VirtualRobotComponent::Activate() { start_ns_ = last_step_ns_ = ctx_.NowNs(); }

double VirtualRobotComponent::ElapsedS() const {
  return start_ns_ > 0 ? (ctx_.NowNs() - start_ns_) * 1e-9 : 0.0;
}

double VirtualRobotComponent::TravelledSinceEpochFt() const {
  return InchesToFeet(sim_->Truth().distance_in - epoch_in_);
}

message::Header VirtualRobotComponent::Stamp() const {
  message::Header h;
  h.stamp_ns = ctx_.NowNs();
  return h;
}

void VirtualRobotComponent::OnWheels(const message::WheelCommand& w) {
  left_ftps_ = w.left_speed_ftps;
  right_ftps_ = w.right_speed_ftps;
  last_wheels_ns_ = ctx_.NowNs();
}

void VirtualRobotComponent::Step() {
  const int64_t now = ctx_.NowNs();
  // The base's watchdog: no set-point for a while means stop.
  if (now - last_wheels_ns_ > config_.wheel_command_timeout_s * 1e9) left_ftps_ = right_ftps_ = 0.0;
  // The time since the last step, not the nominal period: a late timer makes a longer step.
  const double step_s = (now - last_step_ns_) * 1e-9;
  last_step_ns_ = now;
  sim_->Step(step_s, left_ftps_, right_ftps_);
  max_step_s_ = std::max(max_step_s_, step_s);
  LogMotionChange();
  const SimTruth t = sim_->Truth();
  if (t.collisions > collisions_) {
    collisions_ = t.collisions;
    ctx_.log->warn("collision: the base touched a wall at ({:.0f}, {:.0f}) in, {:+.1f} in off "
                   "the hallway axis; it stalls there (collision {})",
                   t.X_WR.x_in, t.X_WR.y_in, t.lateral_offset_in, t.collisions);
  }
  Record(t);
}

// The path, and the envelope of §6.4.2 judged on straight runs, away from corners.
void VirtualRobotComponent::Record(const SimTruth& t) {
  const auto& last = path_.back();
  if (std::hypot(t.X_WR.x_in - last.first, t.X_WR.y_in - last.second) > kPathSpacingIn) {
    path_.push_back({t.X_WR.x_in, t.X_WR.y_in});
  }
  const bool settled = t.distance_in > kEnvelopeSettleDistanceIn;
  if (settled && !t.in_ring_hallway) off_ring_in_ += t.distance_in - recorded_distance_in_;
  recorded_distance_in_ = t.distance_in;
  if (settled && t.in_ring_hallway && t.corner_distance_in > kEnvelopeCornerDistanceIn) {
    max_offset_in_ = std::max(max_offset_in_, std::abs(t.lateral_offset_in));
    max_heading_deg_ = std::max(max_heading_deg_, std::abs(RadToDeg(t.heading_error_rad)));
  }
}

// The base starting and coming to rest, on the simulation's clock (the wall clock at real
// time), so a run's log shows when the robot really stopped (e.g. after its link was cut).
void VirtualRobotComponent::LogMotionChange() {
  const bool moving = std::max(std::abs(left_ftps_), std::abs(right_ftps_)) > kAtRestFtps;
  if (moving == moving_) return;
  moving_ = moving;
  ctx_.log->info("truth: base {} at simulated time {:.3f} s", moving ? "moving" : "at rest",
                 ctx_.NowNs() * 1e-9);
}

void VirtualRobotComponent::PublishEncodersAndTruth() {
  MaybeKidnap();
  message::EncoderReading e;
  e.header = Stamp();
  e.left_travel_in = sim_->left_travel_in();
  e.right_travel_in = sim_->right_travel_in();
  out_.encoders.Publish(e);
  const SimTruth t = sim_->Truth();
  message::GroundTruth g;
  g.header = e.header;
  g.x_in = t.X_WR.x_in;
  g.y_in = t.X_WR.y_in;
  g.heading_rad = t.X_WR.theta_rad;
  // Where the camera looks over the whole floor: the place a pose is judged on, live and
  // in a replay alike.
  g.ring_id = t.seen_ring_id;
  g.edge_index = t.seen_edge_index;
  g.offset_in = t.seen_offset_in;
  g.distance_in = t.distance_in;
  g.lateral_offset_in = t.lateral_offset_in;
  g.heading_error_deg = RadToDeg(t.heading_error_rad);
  g.collisions = t.collisions;
  g.forward_in_ring = t.seen_forward_in_ring;
  out_.truth.Publish(g);
}

void VirtualRobotComponent::PublishEcho() {
  message::SonarEcho s;
  s.header = Stamp();
  s.range_in = sim_->Sonar();
  if (out_.echoes.Publish(s)) ++scans_;
}

void VirtualRobotComponent::PublishFrame() {
  message::Image img;
  img.header = Stamp();
  img.width_px = static_cast<uint32_t>(sim_->image_width_px());
  img.height_px = static_cast<uint32_t>(sim_->image_height_px());
  img.step_bytes = img.width_px;
  img.encoding = "mono8";
  img.data = sim_->RenderFrame();
  if (out_.frames.Publish(img)) ++frames_;
}

// The simulation knows the truth, so it is where a declared pose is judged: the first
// LOCALIZED of each recovery (after LOST, the next LOCALIZED is a new one).
void VirtualRobotComponent::OnPose(const message::LocalizationPose& p) {
  if (p.status != message::LocalizationStatus::kLocalized || p.candidate_count == 0) {
    judged_ = false;
    return;
  }
  if (judged_) return;
  judged_ = true;
  const PoseCheck c = Judge(p);
  checks_.push_back(c);
  ctx_.log->info("{}", Describe(c));
  const SimTruth t = sim_->Truth();
  markers_.push_back({t.X_WR.x_in, t.X_WR.y_in, fmt::format("recovered {}", checks_.size())});
  if (config_.kidnap_after_localized_s >= 0.0 && !kidnapped_ && kidnap_at_s_ < 0.0) {
    kidnap_at_s_ = ElapsedS() + config_.kidnap_after_localized_s;
  }
}

PoseCheck VirtualRobotComponent::Judge(const message::LocalizationPose& p) const {
  const SimTruth t = sim_->Truth();
  PoseCheck c;
  c.ring_id = p.best.ring_id;
  c.edge = p.best.edge_index;
  c.forward = p.best.forward;
  c.truth_ring_id = t.seen_ring_id;
  c.truth_edge = t.seen_edge_index;
  c.truth_forward = t.seen_forward_in_ring;
  c.correct = PoseMatchesTruth(c.ring_id, c.edge, c.forward, t);
  c.edges_sensed = p.edges_sensed;
  c.distance_ft = InchesToFeet(t.distance_in - epoch_in_);
  c.time_s = ElapsedS() - epoch_s_;
  return c;
}

// Teleports the robot (a kidnapping) once the configured time after the first pose.
void VirtualRobotComponent::MaybeKidnap() {
  if (kidnapped_ || kidnap_at_s_ < 0.0 || ElapsedS() < kidnap_at_s_) return;
  kidnapped_ = true;
  const SimTruth before = sim_->Truth();
  sim_->Teleport(sim_->RingPosition() + config_.kidnap_jump_in);
  const SimTruth after = sim_->Truth();
  ctx_.log->info("kidnapped: teleported from edge {} to edge {} ({:+.0f} in along the ring)",
                 before.edge_index, after.edge_index, config_.kidnap_jump_in);
  markers_.push_back({after.X_WR.x_in, after.X_WR.y_in, "kidnapped to"});
  path_.push_back({after.X_WR.x_in, after.X_WR.y_in});
  epoch_in_ = after.distance_in;
  epoch_s_ = ElapsedS();
}

std::string VirtualRobotComponent::Summary() const {
  const SimTruth t = sim_->Truth();
  std::string checks;
  for (const PoseCheck& c : checks_) checks += "; " + Describe(c);
  // Keeping up: the frames due in the simulated time run, and the longest simulation step
  // (the step grows when the timer fires late).
  const double sim_s = ElapsedS();
  return fmt::format(
      "start {}; {} frames ({:.0f} due), {} sonar scans served; {:.1f} s simulated at {:g}x real "
      "time, longest step {:.0f} ms (nominal {:.0f}); travelled {:.1f} in, now on edge {} of ring "
      "'{}'; {} "
      "collisions; after 20 ft, beyond 8 ft of corners: max |offset| {:.1f} in, max |heading "
      "error| {:.1f} deg{}{}",
      start_, frames_, sim_s * config_.camera_rate_hz, scans_, sim_s, config_.real_time_factor,
      max_step_s_ * 1e3, 1e3 / config_.sim_rate_hz, t.distance_in, t.edge_index, sim_->ring_id(),
      t.collisions, max_offset_in_, max_heading_deg_,
      off_ring_in_ > 0.0
          ? fmt::format(" ({:.1f} ft outside the ring's hallway, not judged)", off_ring_ft())
          : std::string(),
      checks.empty() ? "; no pose recovered" : checks);
}

}  // namespace stickrep::virtual_robot
