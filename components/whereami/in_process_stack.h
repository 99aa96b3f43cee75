#pragma once

// The deployed graph in one process: the virtual robot's world serves the device topics on
// the simulated clock, and the sonar, camera, locomotion, landmark, localizer and executive
// components run unchanged, wired by topic name as the processes are on DDS. What differs
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
  virtual_robot::WorldSim& sim() { return *sim_; }
  const localizer::LocalizerComponent& localizer() const { return *localizer_; }
  const executive::ExecutiveComponent& executive() const { return *executive_; }
  int frames_rendered() const { return frames_; }
  // What every component counted as dropped, "name: reason x n" per reason.
  std::vector<std::string> Drops() const;

 private:
  struct Part;
  void MakeComponents(const RunSetup& setup);
  void Wire(bool pose_to_executive);
  std::vector<component::Component*> Components();
  void AddWorld(const virtual_robot::VirtualRobotConfig& vr);
  void AddHeartbeats(const std::vector<std::string>& names);
  component::Context& ContextFor(const std::string& name);

  component::SimExecutor executor_;
  std::unique_ptr<virtual_robot::WorldSim> sim_;
  std::shared_ptr<spdlog::logger> log_;
  std::vector<std::unique_ptr<Part>> parts_;  // each component's context and counters
  std::unique_ptr<sonar::SonarComponent> sonar_;
  std::unique_ptr<camera::CameraComponent> camera_;
  std::unique_ptr<locomotion::LocomotionComponent> locomotion_;
  std::unique_ptr<landmark::LandmarkComponent> landmark_;
  std::unique_ptr<localizer::LocalizerComponent> localizer_;
  std::unique_ptr<executive::ExecutiveComponent> executive_;
  double left_ftps_ = 0.0, right_ftps_ = 0.0;
  int64_t last_wheels_ns_ = 0;
  int frames_ = 0;
};

}  // namespace stickrep::whereami
