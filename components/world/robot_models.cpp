#include "world/robot_models.h"

#include <cmath>

#include "common/units.h"

namespace stickrep::world {

RobotModels RobotModelsFromConfig(const sensing::RobotConfig& robot, double mount_yaw_deg) {
  RobotModels m;
  const sensing::SonarRingConfig& ring = robot.sonar_ring;
  m.sonar.count = ring.count;
  m.sonar.spacing_deg = ring.spacing_deg;
  m.sonar.head_radius_in = ring.head_radius_in;
  m.sonar.cone_deg = ring.cone_deg;
  m.sonar.min_range_in = ring.min_range_in;
  m.sonar.max_range_in = ring.max_range_in;
  // The simulator counts sensor k (k * spacing) clockwise from sensor 0; the coaxial sensor
  // must land on the optical axis.
  m.sonar.coaxial_yaw_deg = mount_yaw_deg + robot.camera.coaxial_sensor * ring.spacing_deg;

  const sensing::CameraConfig& cam = robot.camera;
  m.camera.fov_deg = cam.fov_deg;
  m.camera.width_px = cam.image_width_px;
  m.camera.height_px = cam.image_height_px;
  m.camera.mount_yaw_deg = mount_yaw_deg;
  m.camera.k1 = cam.radial_distortion_k1;
  // robot.yaml gives the optical centre's offset from the ring centre along the optical
  // axis; the renderer wants it in the robot's forward/left frame.
  const double yaw_rad = DegToRad(mount_yaw_deg);
  m.camera.mount_forward_in = cam.offset_forward_in * std::cos(yaw_rad);
  m.camera.mount_left_in = cam.offset_forward_in * std::sin(yaw_rad);

  m.base.max_speed_ftps = robot.base.max_speed_ftps;
  m.base.wheel_base_in = robot.base.wheel_base_in;
  return m;
}

RobotModels LoadRobotModels(const std::string& path, double mount_yaw_deg) {
  return RobotModelsFromConfig(sensing::LoadRobotConfigFile(path), mount_yaw_deg);
}

}  // namespace stickrep::world
