#pragma once

// The deployed graph in one process: the virtual robot, sonar, camera, locomotion, landmark,
// localizer and executive components run unchanged on the simulated clock, wired by topic
// name as the processes are on DDS. What differs
// from the deployed system is the transport alone: samples arrive at once, in publication
// order, none lost, and every process's timers run on the one simulated clock.

#include <spdlog/logger.h>

#include <memory>
#include <string>
#include <vector>

#include "camera/camera_component.h"
#include "component/sim_executor.h"
#include "executive/executive_component.h"
#include "landmark/landmark_component.h"
#include "localizer/localizer_component.h"
#include "locomotion/locomotion_component.h"
#include "sonar/sonar_component.h"
#include "virtual_robot/virtual_robot_component.h"
#include "virtual_robot/world_sim.h"
#include "whereami/whereami_run.h"

namespace stickrep::whereami {

// Heartbeats on system/status, as each process's status reporter sends them.
inline constexpr double kInProcessHeartbeatPeriodS = 0.5;

class InProcessStack {
 public:
  // `sim` is the world placed for this run. With `pose_to_executive` false the executive
  // never hears the localizer (measuring runs: the robot travels on whatever the pose).
  InProcessStack(const RunSetup& setup, std::unique_ptr<virtual_robot::WorldSim> sim,
                 std::shared_ptr<spdlog::logger> log, bool pose_to_executive = true);
  ~InProcessStack();

  component::SimExecutor& executor() { return executor_; }
  const component::SimExecutor& executor() const { return executor_; }
  virtual_robot::VirtualRobotComponent& virtual_robot() { return *virtual_robot_; }
  const virtual_robot::VirtualRobotComponent& virtual_robot() const { return *virtual_robot_; }
  virtual_robot::WorldSim& sim() { return virtual_robot_->sim(); }
  const localizer::LocalizerComponent& localizer() const { return *localizer_; }
  const executive::ExecutiveComponent& executive() const { return *executive_; }
  // What every component counted as dropped, "name: reason x n" per reason.
  std::vector<std::string> Drops() const;

 private:
  struct Part;
  void MakeComponents(const RunSetup& setup);
  void Wire(bool pose_to_executive);
  std::vector<component::Component*> Components();
  void AddHeartbeats(const std::vector<std::string>& names);
  component::Context& ContextFor(const std::string& name);

  component::SimExecutor executor_;
  std::shared_ptr<spdlog::logger> log_;
  std::vector<std::unique_ptr<Part>> parts_;  // each component's context and counters
  std::unique_ptr<virtual_robot::VirtualRobotComponent> virtual_robot_;
  std::unique_ptr<sonar::SonarComponent> sonar_;
  std::unique_ptr<camera::CameraComponent> camera_;
  std::unique_ptr<locomotion::LocomotionComponent> locomotion_;
  std::unique_ptr<landmark::LandmarkComponent> landmark_;
  std::unique_ptr<localizer::LocalizerComponent> localizer_;
  std::unique_ptr<executive::ExecutiveComponent> executive_;
};

}  // namespace stickrep::whereami
