#include "locomotion/locomotion_node.h"

#include <fmt/format.h>

#include <cmath>

#include "basePubSubTypes.h"
#include "common/units.h"
#include "locomotion/drive.h"
#include "runtime/endpoint.h"
#include "sensing/robot_config.h"

namespace stickrep::locomotion {

namespace {

class LocomotionNode : public runtime::ProcessNode {
 public:
  void Configure(runtime::NodeContext& ctx) override {
    ctx_ = &ctx;
    const StrictYaml& c = ctx.config;
    const std::string device = c.Get<std::string>("device");
    if (device == "serial") {
      c.Fail("device", "the LabMate serial driver is not built yet; use 'virtual'");
    } else if (device != "virtual") {
      c.Fail("device", "'" + device + "' is not one of: virtual, serial");
    }
    const double control_rate_hz = c.Get<double>("control_rate_hz", 1.0, 200.0, "Hz");
    command_timeout_s_ = c.Get<double>("command_timeout_s", 0.05, 5.0, "s");
    limits_.max_angular_rate_radps = c.Get<double>("max_angular_rate_radps", 0.01, 5.0, "rad/s");
    c.Finish();
    const sensing::RobotConfig robot = sensing::LoadRobotConfigFile(ctx.system.robot_file);
    limits_.max_speed_ftps = robot.base.max_speed_ftps;
    limits_.wheel_base_in = robot.base.wheel_base_in;
    odometer_ = std::make_unique<Odometer>(robot.base.wheel_base_in);

    wheels_ = std::make_unique<runtime::Writer<msgs::WheelCommandPubSubType>>(
        ctx.participant, "device/base/wheel_command");
    odometry_ = std::make_unique<runtime::Writer<msgs::OdometryPubSubType>>(ctx.participant,
                                                                           "robot/odometry");
    commands_ = std::make_unique<runtime::Reader<msgs::MotionCommandPubSubType>>(
        ctx.participant, ctx.executor, "robot/motion/command",
        [this](const msgs::MotionCommand& m) { OnCommand(m); });
    commands_->OnDeadlineMissed([this] { Stop("motion commands stopped arriving (deadline)"); });
    encoders_ = std::make_unique<runtime::Reader<msgs::EncoderReadingPubSubType>>(
        ctx.participant, ctx.executor, "device/base/encoders",
        [this](const msgs::EncoderReading& e) { OnEncoders(e); });
    ctx.executor.AddTimer(1.0 / control_rate_hz, [this] { ControlStep(); });
  }

  void Deactivate() override { Stop("shutting down"); SendWheels(); }

  std::string Summary() const override {
    return fmt::format("{} commands followed, {} stops, odometry {:.1f} in travelled",
                       commands_followed_, stops_, odometer_ ? odometer_->distance_in() : 0.0);
  }

 private:
  void OnCommand(const msgs::MotionCommand& m) {
    ctx_->counters.CountIn();
    if (!std::isfinite(m.linear_speed_ftps()) || !std::isfinite(m.angular_rate_radps())) {
      ctx_->counters.Drop("robot/motion/command", "non-finite speed");
      Stop("rejected a command with a non-finite speed");
      return;
    }
    if (m.mode() == msgs::MOTION_FOLLOW_HALLWAY && !warned_follow_) {
      warned_follow_ = true;
      ctx_->log->warn("hallway following (A3/A4) is not built yet: following the set-points "
                      "as plain velocity commands");
    }
    if (m.mode() == msgs::MOTION_STOP) {
      Stop("stop commanded");
    } else {
      setpoint_ = ToWheelSpeeds(m.linear_speed_ftps(), m.angular_rate_radps(), limits_);
      stopped_ = false;
      commands_followed_++;
    }
    last_command_ns_ = ctx_->now_ns();
  }

  void OnEncoders(const msgs::EncoderReading& e) {
    ctx_->counters.CountIn();
    if (!std::isfinite(e.left_travel_in()) || !std::isfinite(e.right_travel_in())) {
      ctx_->counters.Drop("device/base/encoders", "non-finite wheel travel");
      return;
    }
    if (e.header().stamp_ns() < last_encoder_ns_) {
      ctx_->counters.Drop("device/base/encoders", "time went backwards");
      return;
    }
    const double dt_s = last_encoder_ns_ > 0 ? (e.header().stamp_ns() - last_encoder_ns_) * 1e-9 : 0;
    const Pose2 before = odometer_->pose();
    const double distance_before = odometer_->distance_in();
    last_encoder_ns_ = e.header().stamp_ns();
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
    if (odometry_->Publish(odo, e.header().stamp_ns())) ctx_->counters.CountOut();
  }

  void ControlStep() {
    if (!stopped_ && ctx_->now_ns() - last_command_ns_ > command_timeout_s_ * 1e9) {
      Stop("no motion command for " + fmt::format("{:.2f}", command_timeout_s_) + " s");
    }
    SendWheels();
  }

  void SendWheels() {
    msgs::WheelCommand w;
    w.left_speed_ftps(setpoint_.left_ftps);
    w.right_speed_ftps(setpoint_.right_ftps);
    if (wheels_ && wheels_->Publish(w, ctx_->now_ns())) ctx_->counters.CountOut();
  }

  void Stop(const std::string& why) {
    if (!stopped_) {
      ctx_->log->info("stopping the base: {}", why);
      stops_++;
    }
    stopped_ = true;
    setpoint_ = {};
  }

  runtime::NodeContext* ctx_ = nullptr;
  DriveLimits limits_;
  double command_timeout_s_ = 0.5;
  std::unique_ptr<Odometer> odometer_;
  WheelSpeeds setpoint_;
  bool stopped_ = true;
  bool warned_follow_ = false;
  int64_t last_command_ns_ = 0;
  int64_t last_encoder_ns_ = 0;
  uint64_t commands_followed_ = 0, stops_ = 0;
  std::unique_ptr<runtime::Writer<msgs::WheelCommandPubSubType>> wheels_;
  std::unique_ptr<runtime::Writer<msgs::OdometryPubSubType>> odometry_;
  std::unique_ptr<runtime::Reader<msgs::MotionCommandPubSubType>> commands_;
  std::unique_ptr<runtime::Reader<msgs::EncoderReadingPubSubType>> encoders_;
};

}  // namespace

std::unique_ptr<runtime::ProcessNode> MakeLocomotionNode() {
  return std::make_unique<LocomotionNode>();
}

}  // namespace stickrep::locomotion
