#include "locomotion/locomotion_component.h"

#include <fmt/format.h>

#include <cmath>

#include "common/units.h"

namespace stickrep::locomotion {

namespace {

message::LocomotionState ToMessage(BehaviourState s) {
  switch (s) {
    case BehaviourState::kNoScan: return message::LocomotionState::kNoScan;
    case BehaviourState::kFollowing: return message::LocomotionState::kFollowing;
    case BehaviourState::kStopping: return message::LocomotionState::kStopping;
    case BehaviourState::kTurning: return message::LocomotionState::kTurning;
    case BehaviourState::kObstacle: return message::LocomotionState::kObstacle;
  }
  return message::LocomotionState::kStopped;
}

}  // namespace

std::vector<SonarRange> ToBehaviourScan(const message::SonarScan& scan) {
  std::vector<SonarRange> ranges(scan.range_in.size());
  for (size_t k = 0; k < scan.range_in.size(); ++k) {
    ranges[k] = {scan.range_in[k], scan.state[k] == sonar::ReadingState::kValid,
                 scan.state[k] == sonar::ReadingState::kOutsideFootprint};
  }
  return ranges;
}

LocomotionComponent::LocomotionComponent(component::Context& ctx, const LocomotionConfig& config,
                                         double wheel_base_in, Outputs out)
    : ctx_(ctx),
      limits_(config.limits),
      command_timeout_s_(config.command_timeout_s),
      resend_rate_hz_(config.resend_rate_hz),
      odometer_(wheel_base_in),
      behaviour_(config.behaviour),
      out_(out) {}

std::vector<component::Timer> LocomotionComponent::Timers() {
  return {{1.0 / resend_rate_hz_, [this] { Watchdog(); }}};
}

void LocomotionComponent::Deactivate() {
  Stop("shutting down");
  SendWheels();
}

std::string LocomotionComponent::Summary() const {
  return fmt::format(
      "{} commands followed, {} stops, odometry {:.1f} in travelled; hallway following: {} "
      "turns, {} reversals, {} obstacle stops, {} stalls",
      commands_followed_, stops_, odometer_.distance_in(), turns_, reversals_, obstacle_stops_,
      stalls_);
}

void LocomotionComponent::OnCommand(const message::MotionCommand& m) {
  if (!std::isfinite(m.linear_speed_ftps) || !std::isfinite(m.angular_rate_radps)) {
    ctx_.counters.Drop("robot/motion/command", "non-finite speed");
    Stop("rejected a command with a non-finite speed");
    PublishState("rejected a command with a non-finite speed: base stopped");
    return;
  }
  last_command_ns_ = ctx_.NowNs();
  if (m.mode == message::MotionMode::kStop) {
    Stop("stop commanded");
    return;
  }
  if (m.mode != mode_ || stopped_) behaviour_.Reset();
  mode_ = m.mode;
  stopped_ = false;
  commands_followed_++;
  commanded_speed_ftps_ = m.linear_speed_ftps;
  if (mode_ == message::MotionMode::kVelocity) {
    setpoint_ = ToWheelSpeeds(m.linear_speed_ftps, m.angular_rate_radps, limits_);
    linear_ftps_ = m.linear_speed_ftps;
    angular_radps_ = m.angular_rate_radps;
  }
  // Following the hallway: the behaviour sets the wheels at the next encoder reading.
}

void LocomotionComponent::OnScan(const message::SonarScan& s) {
  if (s.header.stamp_ns < last_scan_ns_) {
    ctx_.counters.Drop("robot/sonar", "time went backwards");
    return;
  }
  last_scan_ns_ = s.header.stamp_ns;
  behaviour_.OnScan(ToBehaviourScan(s), s.header.stamp_ns * 1e-9);
}

void LocomotionComponent::OnEncoders(const message::EncoderReading& e) {
  const int64_t stamp = e.header.stamp_ns;
  if (stamp < last_encoder_ns_) {
    ctx_.counters.Drop("device/base/encoders", "time went backwards");
    return;
  }
  const double dt_s = last_encoder_ns_ > 0 ? (stamp - last_encoder_ns_) * 1e-9 : 0.0;
  const Pose2 before = odometer_.pose();
  const double distance_before = odometer_.distance_in();
  last_encoder_ns_ = stamp;
  odometer_.Update(e.left_travel_in, e.right_travel_in);
  message::Odometry odo;
  odo.header.stamp_ns = stamp;
  odo.x_in = odometer_.pose().x_in;
  odo.y_in = odometer_.pose().y_in;
  odo.heading_rad = odometer_.pose().heading_rad;
  odo.distance_in = odometer_.distance_in();
  if (dt_s > 0) {
    odo.linear_speed_ftps = InchesToFeet(odometer_.distance_in() - distance_before) / dt_s;
    odo.angular_rate_radps =
        std::remainder(odometer_.pose().heading_rad - before.heading_rad, 2 * kPi) / dt_s;
  }
  out_.odometry.Publish(odo);
  if (!stopped_ && mode_ == message::MotionMode::kFollowHallway) Follow(stamp * 1e-9, dt_s);
}

// One step of hallway following at the base's time `now_s`.
void LocomotionComponent::Follow(double now_s, double dt_s) {
  const BehaviourOutput out = behaviour_.Step(commanded_speed_ftps_, odometer_.pose().heading_rad,
                                              odometer_.distance_in(), now_s, dt_s);
  setpoint_ = ToWheelSpeeds(out.linear_ftps, out.angular_radps, limits_);
  linear_ftps_ = out.linear_ftps;
  angular_radps_ = out.angular_radps;
  behaviour_state_ = out.state;
  envelope_ = out;
  if (out.turn_started) {
    turns_++;
    ctx_.log->info("{}", out.reason);
  }
  if (out.reversed) {
    reversals_++;
    // A stall is a contact the sonar missed: always worth a warning.
    if (out.stalled) {
      stalls_++;
      ctx_.log->warn("{}", out.reason);
    } else {
      ctx_.log->info("{}", out.reason);
    }
  }
  if (out.obstacle_stop_started) {
    obstacle_stops_++;
    ctx_.log->warn("{}", out.reason);
  }
  if (out.state != logged_state_) {
    ctx_.log->info("hallway behaviour: {} ({})", ToString(out.state), out.reason);
    logged_state_ = out.state;
  }
  SendWheels();
  PublishState(out.reason);
}

void LocomotionComponent::Watchdog() {
  if (!stopped_ && ctx_.NowNs() - last_command_ns_ > command_timeout_s_ * 1e9) {
    Stop(fmt::format("no motion command for {:.2f} s", command_timeout_s_));
  }
  SendWheels();
  if (stopped_ || mode_ != message::MotionMode::kFollowHallway) PublishState("");
}

void LocomotionComponent::SendWheels() {
  message::WheelCommand w;
  w.header.stamp_ns = ctx_.NowNs();
  w.left_speed_ftps = setpoint_.left_ftps;
  w.right_speed_ftps = setpoint_.right_ftps;
  out_.wheels.Publish(w);
}

void LocomotionComponent::PublishState(const std::string& text) {
  message::MotionState s;
  s.mode = stopped_ ? message::MotionMode::kStop : mode_;
  s.travel_sign = behaviour_.travel_sign();
  s.commanded_speed_ftps = stopped_ ? 0.0 : commanded_speed_ftps_;
  s.linear_speed_ftps = linear_ftps_;
  s.angular_rate_radps = angular_radps_;
  if (stopped_) {
    s.state = message::LocomotionState::kStopped;
    s.message = text.empty() ? "stopped: " + stop_reason_ : text;
  } else if (mode_ == message::MotionMode::kVelocity) {
    s.state = message::LocomotionState::kVelocity;
    s.message = text.empty() ? "following velocity set-points" : text;
  } else {
    s.state = ToMessage(behaviour_state_);
    s.offset_valid = envelope_.offset_valid;
    s.lateral_offset_in = envelope_.lateral_offset_in;
    s.heading_valid = envelope_.heading_valid;
    s.heading_error_deg = RadToDeg(envelope_.heading_error_rad);
    s.in_envelope = envelope_.in_envelope;
    s.message = text;
  }
  // Stamped on the base's clock (the encoders'), as the odometry is.
  s.header.stamp_ns = last_encoder_ns_ > 0 ? last_encoder_ns_ : ctx_.NowNs();
  out_.state.Publish(s);
}

void LocomotionComponent::Stop(const std::string& why) {
  if (!stopped_) {
    ctx_.log->info("stopping the base: {}", why);
    stops_++;
    stop_reason_ = why;
  }
  stopped_ = true;
  setpoint_ = {};
  linear_ftps_ = angular_radps_ = 0.0;
  envelope_ = {};
  behaviour_.Reset();
}

}  // namespace stickrep::locomotion
