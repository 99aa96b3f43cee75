#pragma once

#include <map>
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
  // A floor's own hallway behaviour, where it differs, by the map's name (MapInfo::name):
  // `behaviour` with the keys of the floor's block in place (ForMap picks one).
  std::map<std::string, HallwayBehaviourConfig> on_maps;
};

// Reads the `locomotion` section; every key required but the `on_maps` block (under each map
// name, any of the `hallway` keys), unknown keys rejected (InputError with file, line and key).
// 'serial' is refused: the LabMate driver is not built.
LocomotionConfig LoadLocomotionConfig(const StrictYaml& section, const sensing::RobotConfig& robot);

// `config` with the hallway behaviour for the map named `map_name`: its on_maps entry where
// there is one, else the default; on_maps emptied.
LocomotionConfig ForMap(LocomotionConfig config, const std::string& map_name);

// The behaviour's ring geometry and speed limit from the robot description.
void ApplyRobot(const sensing::RobotConfig& robot, HallwayBehaviourConfig& behaviour);

}  // namespace stickrep::locomotion
