#include "whereami/in_process_stack.h"

#include <fmt/format.h>

namespace stickrep::whereami {

struct InProcessStack::Part {
  Part(const std::string& name, const component::Clock& clock,
       std::shared_ptr<spdlog::logger> log)
      : counters(log), context{name, clock, log, counters} {}
  component::SampleCounters counters;
  component::Context context;
};

component::Context& InProcessStack::ContextFor(const std::string& name) {
  parts_.push_back(std::make_unique<Part>(name, executor_, log_));
  return parts_.back()->context;
}

InProcessStack::InProcessStack(const RunSetup& setup, std::unique_ptr<virtual_robot::WorldSim> sim,
                               std::shared_ptr<spdlog::logger> log, bool pose_to_executive)
    : log_(std::move(log)) {
  component::SimExecutor& e = executor_;
  // The virtual robot first: at each instant the world steps, then the devices are read,
  // before the processes' timers run.
  virtual_robot_ = std::make_unique<virtual_robot::VirtualRobotComponent>(
      ContextFor("virtual_robot"), setup.virtual_robot, std::move(sim),
      virtual_robot::VirtualRobotComponent::Outputs{
          e.Advertise<message::SonarEcho>("device/sonar/echo"),
          e.Advertise<message::Image>("device/camera/frame"),
          e.Advertise<message::EncoderReading>("device/base/encoders"),
          e.Advertise<message::GroundTruth>("sim/ground_truth")});
  MakeComponents(setup);
  Wire(pose_to_executive);
  for (component::Component* c : Components()) e.AddTimers(*c);
  // Every component the executive may require beats, as each process's status reporter does.
  std::vector<std::string> beating;
  for (const auto& p : parts_) {
    const std::string& name = p->context.name;
    if (name != "executive" && name != "virtual_robot") beating.push_back(name);
  }
  AddHeartbeats(beating);
  for (component::Component* c : Components()) c->Activate();
  e.Deliver();
}

InProcessStack::~InProcessStack() = default;

std::vector<component::Component*> InProcessStack::Components() {
  return {virtual_robot_.get(), sonar_.get(),     camera_.get(),   locomotion_.get(),
          landmark_.get(),      localizer_.get(), executive_.get()};
}

// Each component with its publishers, as its node makes it.
void InProcessStack::MakeComponents(const RunSetup& setup) {
  component::SimExecutor& e = executor_;
  const sensing::RobotConfig& robot = setup.robot;
  sonar_ = std::make_unique<sonar::SonarComponent>(ContextFor("sonar"), sonar::GateConfigFor(robot),
                                                   e.Advertise<message::SonarScan>("robot/sonar"));
  camera_ = std::make_unique<camera::CameraComponent>(
      ContextFor("camera"), static_cast<uint32_t>(robot.camera.image_width_px),
      static_cast<uint32_t>(robot.camera.image_height_px),
      e.Advertise<message::Image>("robot/camera/image"));
  locomotion_ = std::make_unique<locomotion::LocomotionComponent>(
      ContextFor("locomotion"), setup.locomotion, robot.base.wheel_base_in,
      locomotion::LocomotionComponent::Outputs{
          e.Advertise<message::WheelCommand>("device/base/wheel_command"),
          e.Advertise<message::Odometry>("robot/odometry"),
          e.Advertise<message::MotionState>("robot/motion/state")});
  landmark_ = std::make_unique<landmark::LandmarkComponent>(
      ContextFor("landmark"), robot, setup.landmark,
      e.Advertise<message::LandmarkObservation>("perception/landmark"));
  localizer_ = std::make_unique<localizer::LocalizerComponent>(
      ContextFor("localizer"), *setup.map, setup.localizer, robot,
      localizer::LocalizerComponent::Outputs{
          e.Advertise<message::LocalizationPose>("localization/pose"),
          e.Advertise<message::PoseHypotheses>("localization/hypotheses")});
  executive_ = std::make_unique<executive::ExecutiveComponent>(
      ContextFor("executive"), *setup.map, setup.executive, "robot", nullptr,
      executive::ExecutiveComponent::Outputs{
          e.Advertise<message::MotionCommand>("robot/motion/command"),
          e.Advertise<message::MissionStatus>("mission/status"),
          e.Advertise<message::MissionGoalResult>("mission/goal_result")});
}

// The topics each process reads, as its node feeds them.
void InProcessStack::Wire(bool pose_to_executive) {
  component::SimExecutor& e = executor_;
  e.Subscribe<message::WheelCommand>(
      "device/base/wheel_command",
      [this](const message::WheelCommand& w) { virtual_robot_->OnWheels(w); });
  e.Subscribe<message::LocalizationPose>(
      "localization/pose",
      [this](const message::LocalizationPose& p) { virtual_robot_->OnPose(p); });
  e.Subscribe<message::SonarEcho>("device/sonar/echo",
                                  [this](const message::SonarEcho& s) { sonar_->OnEcho(s); });
  e.Subscribe<message::Image>("device/camera/frame",
                              [this](const message::Image& f) { camera_->OnFrame(f); });
  e.Subscribe<message::MotionCommand>(
      "robot/motion/command", [this](const message::MotionCommand& m) { locomotion_->OnCommand(m); });
  e.Subscribe<message::EncoderReading>(
      "device/base/encoders", [this](const message::EncoderReading& r) { locomotion_->OnEncoders(r); });
  e.Subscribe<message::SonarScan>("robot/sonar",
                                  [this](const message::SonarScan& s) { locomotion_->OnScan(s); });
  e.Subscribe<message::SonarScan>("robot/sonar",
                                  [this](const message::SonarScan& s) { landmark_->OnScan(s); });
  e.Subscribe<message::Odometry>("robot/odometry",
                                 [this](const message::Odometry& o) { landmark_->OnOdometry(o); });
  e.Subscribe<message::Image>("robot/camera/image",
                              [this](const message::Image& m) { landmark_->OnImage(m); });
  e.Subscribe<message::LandmarkObservation>(
      "perception/landmark",
      [this](const message::LandmarkObservation& o) { localizer_->OnLandmark(o); });
  e.Subscribe<message::SonarScan>("robot/sonar",
                                  [this](const message::SonarScan& s) { localizer_->OnSonar(s); });
  e.Subscribe<message::Odometry>("robot/odometry",
                                 [this](const message::Odometry& o) { localizer_->OnOdometry(o); });
  e.Subscribe<message::Odometry>("robot/odometry",
                                 [this](const message::Odometry& o) { executive_->OnOdometry(o); });
  e.Subscribe<message::ComponentStatus>(
      "system/status", [this](const message::ComponentStatus& s) { executive_->OnHeartbeat(s); });
  if (pose_to_executive) {
    e.Subscribe<message::LocalizationPose>(
        "localization/pose", [this](const message::LocalizationPose& p) { executive_->OnPose(p); });
  }
  e.Subscribe<message::MotionState>(
      "robot/motion/state", [this](const message::MotionState& m) { executive_->OnMotionState(m); });
  e.Subscribe<message::MissionGoal>(
      "mission/goal", [this](const message::MissionGoal& g) { executive_->OnGoal(g); });
}

void InProcessStack::AddHeartbeats(const std::vector<std::string>& names) {
  auto& status = executor_.Advertise<message::ComponentStatus>("system/status");
  const auto beat = [this, &status, names] {
    for (const std::string& name : names) {
      message::ComponentStatus s;
      s.header.stamp_ns = executor_.NowNs();
      s.component_name = name;
      s.state = message::ComponentState::kActive;
      s.host = "robot";
      status.Publish(s);
    }
  };
  executor_.AddTimer(kInProcessHeartbeatPeriodS, beat, 0.0);
}

std::vector<std::string> InProcessStack::Drops() const {
  std::vector<std::string> out;
  for (const auto& p : parts_) {
    for (const auto& [reason, n] : p->counters.dropped_by_reason()) {
      out.push_back(fmt::format("{}: {} x {}", p->context.name, reason, n));
    }
  }
  return out;
}

}  // namespace stickrep::whereami
