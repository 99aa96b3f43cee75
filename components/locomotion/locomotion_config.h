#pragma once

#include <string>

#include "common/strict_yaml.h"
#include "locomotion/drive.h"
#include "locomotion/hallway_behaviour.h"
#include "sensing/robot_config.h"

namespace stickrep::locomotion {

// The locomotion process's settings (configs/locomotion.yaml) with the base and sonar ring
// of the robot description filled in.
struct LocomotionConfig {
  std::string device = "virtual";   // 'virtual' (the virtual robot's device topics)
  double resend_rate_hz = 20.0;     // wheel set-points re-sent at this rate (base watchdog)
  double command_timeout_s = 0.5;   // no motion command for this long: stop
  DriveLimits limits;
  HallwayBehaviourConfig behaviour;
};

// Reads the `locomotion` section; every key required, unknown keys rejected (InputError with
// file, line and key). 'serial' is refused: the LabMate driver is not built.
LocomotionConfig LoadLocomotionConfig(const StrictYaml& section, const sensing::RobotConfig& robot);

// The behaviour's ring geometry and speed limit from the robot description.
void ApplyRobot(const sensing::RobotConfig& robot, HallwayBehaviourConfig& behaviour);

}  // namespace stickrep::locomotion
