#pragma once

#include <memory>
#include <string>

#include "component/component.h"
#include "locomotion/drive.h"
#include "locomotion/hallway_behaviour.h"
#include "locomotion/locomotion_config.h"
#include "messages/messages.h"

namespace stickrep::locomotion {

// The locomotion process's logic, the base: wheel set-points out, encoders in, odometry
// published. Following the hallway, the behaviour steers on the gated sonar scans and steps
// on every encoder reading, in the base's own time (the encoders' stamps); a timer on the
// component's clock re-sends the set-point for the base's watchdog and stops the base when
// motion commands stop arriving.
class LocomotionComponent : public component::Component {
 public:
  struct Outputs {
    component::Publisher<message::WheelCommand>& wheels;
    component::Publisher<message::Odometry>& odometry;
    component::Publisher<message::MotionState>& state;
  };
  LocomotionComponent(component::Context& ctx, const LocomotionConfig& config,
                      double wheel_base_in, Outputs out);

  void OnCommand(const message::MotionCommand& command);
  void OnScan(const message::SonarScan& scan);
  void OnEncoders(const message::EncoderReading& encoders);
  // The command stream's deadline passed (DDS QoS): stop.
  void OnCommandsSilent() { Stop("motion commands stopped arriving (deadline)"); }
  // The command timeout, and the set-point re-sent for the base's watchdog.
  void Watchdog();

  std::vector<component::Timer> Timers() override;
  void Deactivate() override;
  std::string Summary() const override;

 private:
  void Follow(double now_s, double dt_s);
  void SendWheels();
  void PublishState(const std::string& text);
  void Stop(const std::string& why);

  component::Context& ctx_;
  DriveLimits limits_;
  double command_timeout_s_;
  double resend_rate_hz_;
  Odometer odometer_;
  HallwayBehaviour behaviour_;
  Outputs out_;
  message::MotionMode mode_ = message::MotionMode::kStop;
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
  uint64_t commands_followed_ = 0, stops_ = 0, turns_ = 0, reversals_ = 0, obstacle_stops_ = 0,
           stalls_ = 0;
};

// The gated scan as the hallway behaviour reads it.
std::vector<SonarRange> ToBehaviourScan(const message::SonarScan& scan);

}  // namespace stickrep::locomotion
