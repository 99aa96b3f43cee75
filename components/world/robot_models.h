#pragma once

#include <string>

#include "sensing/robot_config.h"
#include "world/camera_renderer.h"
#include "world/diff_drive.h"
#include "world/sonar_ring.h"

namespace stickrep::world {

// The simulated robot's sensor and base models, filled from the one robot description
// (configs/robot.yaml, sensing::RobotConfig) so the world, the landmark pipeline and the
// processes agree on every shared number. Fields configs/robot.yaml does not carry (camera
// and sonar heights, roll, lens distortion, wheel slip, the sideways mounting of §6.4.2)
// keep the world's documented defaults.
struct RobotModels {
  SonarRingModel sonar;
  CameraModel camera;
  BaseModel base;
};

// Fills the models from `robot`. The camera looks `mount_yaw_deg` left of the heading
// (+90°: sideways, §6.4.2); sensor robot.camera.coaxial_sensor is on the optical axis
// (constraint C3, §5.1), so sensor 0 points coaxial_sensor spacings to the image's left of
// it; the camera's offset_forward_in lies along the optical axis.
RobotModels RobotModelsFromConfig(const sensing::RobotConfig& robot, double mount_yaw_deg = 90.0);

// Loads and validates `path` (configs/robot.yaml format) and fills the models. Throws
// InputError naming file, line and key on bad input.
RobotModels LoadRobotModels(const std::string& path, double mount_yaw_deg = 90.0);

}  // namespace stickrep::world
