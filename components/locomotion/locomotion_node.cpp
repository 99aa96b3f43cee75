#include "locomotion/locomotion_node.h"

#include <fmt/format.h>

#include <cmath>
#include <vector>

#include "basePubSubTypes.h"
#include "common/units.h"
#include "locomotion/drive.h"
#include "locomotion/hallway_behaviour.h"
#include "locomotion/locomotion_config.h"
#include "runtime/endpoint.h"
#include "sensing/robot_config.h"
#include "sensorsPubSubTypes.h"

namespace stickrep::locomotion {

namespace {

msgs::LocomotionState ToMsg(BehaviourState s) {
  switch (s) {
    case BehaviourState::kNoScan: return msgs::LOCOMOTION_NO_SCAN;
    case BehaviourState::kFollowing: return msgs::LOCOMOTION_FOLLOWING;
    case BehaviourState::kStopping: return msgs::LOCOMOTION_STOPPING;
    case BehaviourState::kTurning: return msgs::LOCOMOTION_TURNING;
    case BehaviourState::kObstacle: return msgs::LOCOMOTION_OBSTACLE;
  }
  return msgs::LOCOMOTION_STOPPED;
}

// The base: wheel set-points out, encoders in, odometry published. In MOTION_FOLLOW_HALLWAY
// the hallway behaviour steers on the gated sonar scans; it steps on every encoder reading,
// in the base's own time (the virtual robot's simulated clock runs faster than the wall
// clock), while a wall-clock timer re-sends the set-point for the base's watchdog and the
// command deadline stops the base when the executive falls silent.
class LocomotionNode : public runtime::ProcessNode {
 public:
  void Configure(runtime::NodeContext& ctx) override {
    ctx_ = &ctx;
    const sensing::RobotConfig robot = sensing::LoadRobotConfigFile(ctx.system.robot_file);
    const LocomotionConfig config = LoadLocomotionConfig(ctx.config, robot);
    limits_ = config.limits;
    command_timeout_s_ = config.command_timeout_s;
    behaviour_ = std::make_unique<HallwayBehaviour>(config.behaviour);
    odometer_ = std::make_unique<Odometer>(robot.base.wheel_base_in);

    wheels_ = std::make_unique<runtime::Writer<msgs::WheelCommandPubSubType>>(
        ctx.participant, "device/base/wheel_command");
    odometry_ = std::make_unique<runtime::Writer<msgs::OdometryPubSubType>>(ctx.participant,
                                                                           "robot/odometry");
    state_ = std::make_unique<runtime::Writer<msgs::MotionStatePubSubType>>(ctx.participant,
                                                                           "robot/motion/state");
    commands_ = std::make_unique<runtime::Reader<msgs::MotionCommandPubSubType>>(
        ctx.participant, ctx.executor, "robot/motion/command",
        [this](const msgs::MotionCommand& m) { OnCommand(m); });
    commands_->OnDeadlineMissed([this] { Stop("motion commands stopped arriving (deadline)"); });
    encoders_ = std::make_unique<runtime::Reader<msgs::EncoderReadingPubSubType>>(
        ctx.participant, ctx.executor, "device/base/encoders",
        [this](const msgs::EncoderReading& e) { OnEncoders(e); });
    scans_ = std::make_unique<runtime::Reader<msgs::SonarScanPubSubType>>(
        ctx.participant, ctx.executor, "robot/sonar",
        [this](const msgs::SonarScan& s) { OnScan(s); });
    ctx.executor.AddTimer(1.0 / config.resend_rate_hz, [this] { Watchdog(); });
  }

  void Deactivate() override {
    Stop("shutting down");
    SendWheels();
  }

  std::string Summary() const override {
    return fmt::format(
        "{} commands followed, {} stops, odometry {:.1f} in travelled; hallway following: {} "
        "turns, {} reversals, {} obstacle stops",
        commands_followed_, stops_, odometer_ ? odometer_->distance_in() : 0.0, turns_,
        reversals_, obstacle_stops_);
  }

 private:
  void OnCommand(const msgs::MotionCommand& m) {
    ctx_->counters.CountIn();
    if (!std::isfinite(m.linear_speed_ftps()) || !std::isfinite(m.angular_rate_radps())) {
      ctx_->counters.Drop("robot/motion/command", "non-finite speed");
      Stop("rejected a command with a non-finite speed");
      PublishState("rejected a command with a non-finite speed: base stopped");
      return;
    }
    last_command_ns_ = ctx_->now_ns();
    if (m.mode() == msgs::MOTION_STOP) {
      Stop("stop commanded");
      return;
    }
    if (m.mode() != mode_ || stopped_) behaviour_->Reset();
    mode_ = m.mode();
    stopped_ = false;
    commands_followed_++;
    commanded_speed_ftps_ = m.linear_speed_ftps();
    if (mode_ == msgs::MOTION_VELOCITY) {
      setpoint_ = ToWheelSpeeds(m.linear_speed_ftps(), m.angular_rate_radps(), limits_);
      linear_ftps_ = m.linear_speed_ftps();
      angular_radps_ = m.angular_rate_radps();
    }
    // MOTION_FOLLOW_HALLWAY: the behaviour sets the wheels at the next encoder reading.
  }

  void OnScan(const msgs::SonarScan& s) {
    ctx_->counters.CountIn();
    std::vector<SonarRange> scan(s.range_in().size());
    for (size_t k = 0; k < s.range_in().size(); ++k) {
      const double r = s.range_in()[k];
      const msgs::SonarReadingState st = s.reading_state()[k];
      const bool echo = st == msgs::SONAR_VALID || st == msgs::SONAR_OUTSIDE_FOOTPRINT;
      if (echo && (!std::isfinite(r) || r <= 0.0)) {
        ctx_->counters.Drop("robot/sonar", "a reading with an echo is not a positive range");
        return;
      }
      scan[k] = {r, st == msgs::SONAR_VALID, st == msgs::SONAR_OUTSIDE_FOOTPRINT};
    }
    if (s.header().stamp_ns() < last_scan_ns_) {
      ctx_->counters.Drop("robot/sonar", "time went backwards");
      return;
    }
    last_scan_ns_ = s.header().stamp_ns();
    behaviour_->OnScan(scan, s.header().stamp_ns() * 1e-9);
  }

  void OnEncoders(const msgs::EncoderReading& e) {
    ctx_->counters.CountIn();
    if (!std::isfinite(e.left_travel_in()) || !std::isfinite(e.right_travel_in())) {
      ctx_->counters.Drop("device/base/encoders", "non-finite wheel travel");
      return;
    }
    const int64_t stamp = e.header().stamp_ns();
    if (stamp < last_encoder_ns_) {
      ctx_->counters.Drop("device/base/encoders", "time went backwards");
      return;
    }
    const double dt_s = last_encoder_ns_ > 0 ? (stamp - last_encoder_ns_) * 1e-9 : 0.0;
    const Pose2 before = odometer_->pose();
    const double distance_before = odometer_->distance_in();
    last_encoder_ns_ = stamp;
    odometer_->Update(e.left_travel_in(), e.right_travel_in());
    msgs::Odometry odo;
    odo.pose().x_in(odometer_->pose().x_in);
    odo.pose().y_in(odometer_->pose().y_in);
    odo.pose().heading_rad(odometer_->pose().heading_rad);
    odo.distance_in(odometer_->distance_in());
    if (dt_s > 0) {
      odo.linear_speed_ftps(InchesToFeet(odometer_->distance_in() - distance_before) / dt_s);
      odo.angular_rate_radps(
          std::remainder(odometer_->pose().heading_rad - before.heading_rad, 2 * kPi) / dt_s);
    }
    if (odometry_->Publish(odo, stamp)) ctx_->counters.CountOut();
    if (!stopped_ && mode_ == msgs::MOTION_FOLLOW_HALLWAY) Follow(stamp * 1e-9, dt_s);
  }

  // One step of hallway following at the base's time `now_s`.
  void Follow(double now_s, double dt_s) {
    const BehaviourOutput out = behaviour_->Step(commanded_speed_ftps_,
                                                 odometer_->pose().heading_rad,
                                                 odometer_->distance_in(), now_s, dt_s);
    setpoint_ = ToWheelSpeeds(out.linear_ftps, out.angular_radps, limits_);
    linear_ftps_ = out.linear_ftps;
    angular_radps_ = out.angular_radps;
    behaviour_state_ = out.state;
    envelope_ = out;
    if (out.turn_started) {
      turns_++;
      ctx_->log->info("{}", out.reason);
    }
    if (out.reversed) {
      reversals_++;
      ctx_->log->info("{}", out.reason);
    }
    if (out.obstacle_stop_started) {
      obstacle_stops_++;
      ctx_->log->warn("{}", out.reason);
    }
    if (out.state != logged_state_) {
      ctx_->log->info("hallway behaviour: {} ({})", ToString(out.state), out.reason);
      logged_state_ = out.state;
    }
    SendWheels();
    PublishState(out.reason);
  }

  // Wall clock: the command timeout, and the set-point re-sent for the base's watchdog.
  void Watchdog() {
    if (!stopped_ && ctx_->now_ns() - last_command_ns_ > command_timeout_s_ * 1e9) {
      Stop(fmt::format("no motion command for {:.2f} s", command_timeout_s_));
    }
    SendWheels();
    if (stopped_ || mode_ != msgs::MOTION_FOLLOW_HALLWAY) PublishState("");
  }

  void SendWheels() {
    msgs::WheelCommand w;
    w.left_speed_ftps(setpoint_.left_ftps);
    w.right_speed_ftps(setpoint_.right_ftps);
    if (wheels_ && wheels_->Publish(w, ctx_->now_ns())) ctx_->counters.CountOut();
  }

  void PublishState(const std::string& message) {
    msgs::MotionState s;
    s.mode(stopped_ ? msgs::MOTION_STOP : mode_);
    s.travel_sign(behaviour_->travel_sign());
    s.commanded_speed_ftps(stopped_ ? 0.0 : commanded_speed_ftps_);
    s.linear_speed_ftps(linear_ftps_);
    s.angular_rate_radps(angular_radps_);
    if (stopped_) {
      s.state(msgs::LOCOMOTION_STOPPED);
      s.message(message.empty() ? "stopped: " + stop_reason_ : message);
    } else if (mode_ == msgs::MOTION_VELOCITY) {
      s.state(msgs::LOCOMOTION_VELOCITY);
      s.message(message.empty() ? "following velocity set-points" : message);
    } else {
      s.state(ToMsg(behaviour_state_));
      s.offset_valid(envelope_.offset_valid);
      s.lateral_offset_in(envelope_.lateral_offset_in);
      s.heading_valid(envelope_.heading_valid);
      s.heading_error_deg(RadToDeg(envelope_.heading_error_rad));
      s.in_envelope(envelope_.in_envelope);
      s.message(message);
    }
    // Stamped on the base's clock (the encoders'), as the odometry is.
    const int64_t stamp = last_encoder_ns_ > 0 ? last_encoder_ns_ : ctx_->now_ns();
    if (state_->Publish(s, stamp)) ctx_->counters.CountOut();
  }

  void Stop(const std::string& why) {
    if (!stopped_) {
      ctx_->log->info("stopping the base: {}", why);
      stops_++;
      stop_reason_ = why;
    }
    stopped_ = true;
    setpoint_ = {};
    linear_ftps_ = angular_radps_ = 0.0;
    envelope_ = {};
    if (behaviour_) behaviour_->Reset();
  }

  runtime::NodeContext* ctx_ = nullptr;
  DriveLimits limits_;
  double command_timeout_s_ = 0.5;
  std::unique_ptr<Odometer> odometer_;
  std::unique_ptr<HallwayBehaviour> behaviour_;
  msgs::MotionMode mode_ = msgs::MOTION_STOP;
  double commanded_speed_ftps_ = 0.0;
  WheelSpeeds setpoint_;
  double linear_ftps_ = 0.0, angular_radps_ = 0.0;
  BehaviourState behaviour_state_ = BehaviourState::kNoScan;
  BehaviourState logged_state_ = BehaviourState::kNoScan;
  BehaviourOutput envelope_;
  bool stopped_ = true;
  std::string stop_reason_ = "no command yet";
  int64_t last_command_ns_ = 0;
  int64_t last_encoder_ns_ = 0;
  int64_t last_scan_ns_ = 0;
  uint64_t commands_followed_ = 0, stops_ = 0, turns_ = 0, reversals_ = 0, obstacle_stops_ = 0;
  std::unique_ptr<runtime::Writer<msgs::WheelCommandPubSubType>> wheels_;
  std::unique_ptr<runtime::Writer<msgs::OdometryPubSubType>> odometry_;
  std::unique_ptr<runtime::Writer<msgs::MotionStatePubSubType>> state_;
  std::unique_ptr<runtime::Reader<msgs::MotionCommandPubSubType>> commands_;
  std::unique_ptr<runtime::Reader<msgs::EncoderReadingPubSubType>> encoders_;
  std::unique_ptr<runtime::Reader<msgs::SonarScanPubSubType>> scans_;
};

}  // namespace

std::unique_ptr<runtime::ProcessNode> MakeLocomotionNode() {
  return std::make_unique<LocomotionNode>();
}

}  // namespace stickrep::locomotion
