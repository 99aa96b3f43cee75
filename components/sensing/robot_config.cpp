#include "sensing/robot_config.h"

#include <cmath>

#include "common/config_paths.h"
#include "common/units.h"

namespace stickrep::sensing {

void SonarRingConfig::Validate(const StrictYaml& where) const {
  if (std::abs(count * spacing_deg - 360.0) > 1e-6) {
    where.Fail("spacing_deg", "count (" + std::to_string(count) + ") times spacing_deg (" +
                                  std::to_string(spacing_deg) +
                                  " deg) must close the ring at 360 deg");
  }
  if (min_range_in >= max_range_in) {
    where.Fail("max_range_in", "max_range_in (in) must exceed min_range_in (" +
                                   std::to_string(min_range_in) + " in)");
  }
  if (footprint_deg > 45.0) {
    where.Fail("footprint_deg",
               "an accurate footprint wider than 45 deg contradicts Tables 4.2/4.3 (gross "
               "errors beyond 45 deg)");
  }
}

void CameraConfig::Validate(const StrictYaml& where, const SonarRingConfig& ring) const {
  const double half_width_mm = pixel_pitch_mm * image_width_px / 2.0;
  const double fov_from_pitch_deg = 2.0 * RadToDeg(std::atan(half_width_mm / focal_length_mm));
  if (std::abs(fov_from_pitch_deg - fov_deg) > 0.5) {
    where.Fail("pixel_pitch_mm",
               "pixel_pitch_mm * image_width_px / 2 / focal_length_mm gives a field of view of " +
                   std::to_string(fov_from_pitch_deg) + " deg, but fov_deg is " +
                   std::to_string(fov_deg) + " deg (they must agree within 0.5 deg)");
  }
  if (coaxial_sensor >= ring.count) {
    where.Fail("coaxial_sensor", "coaxial_sensor must be below sonar_ring.count (" +
                                     std::to_string(ring.count) + ")");
  }
}

RobotConfig LoadRobotConfig(const StrictYaml& root) {
  RobotConfig cfg;
  const StrictYaml robot = root.Child("robot");

  const StrictYaml ring = robot.Child("sonar_ring");
  SonarRingConfig& s = cfg.sonar_ring;
  s.count = ring.Get<int>("count", 3, 64, "sensors");
  s.spacing_deg = ring.Get<double>("spacing_deg", 1.0, 120.0, "deg");
  s.head_radius_in = ring.Get<double>("head_radius_in", 1.0, 24.0, "in");
  s.cone_deg = ring.Get<double>("cone_deg", 1.0, 90.0, "deg");
  s.min_range_in = ring.Get<double>("min_range_in", 1.0, 120.0, "in");
  s.max_range_in = ring.Get<double>("max_range_in", 24.0, 1200.0, "in");
  s.footprint_deg = ring.Get<double>("footprint_deg", 0.0, 90.0, "deg");
  ring.Finish();
  s.Validate(ring);

  const StrictYaml cam = robot.Child("camera");
  CameraConfig& c = cfg.camera;
  c.fov_deg = cam.Get<double>("fov_deg", 10.0, 120.0, "deg");
  c.image_width_px = cam.Get<int>("image_width_px", 16, 8192, "px");
  c.image_height_px = cam.Get<int>("image_height_px", 16, 8192, "px");
  c.focal_length_mm = cam.Get<double>("focal_length_mm", 1.0, 100.0, "mm");
  c.pixel_pitch_mm = cam.Get<double>("pixel_pitch_mm", 0.0005, 0.1, "mm");
  c.coaxial_sensor = cam.Get<int>("coaxial_sensor", 0, 63, "");
  c.offset_forward_in = cam.Get<double>("offset_forward_in", -24.0, 24.0, "in");
  c.radial_distortion_k1 = cam.Get<double>("radial_distortion_k1", -0.3, 0.5, "");
  c.frame_rate_hz = cam.Get<double>("frame_rate_hz", 0.5, 120.0, "Hz");
  cam.Finish();
  c.Validate(cam, s);

  const StrictYaml base = robot.Child("base");
  BaseConfig& b = cfg.base;
  b.max_speed_ftps = base.Get<double>("max_speed_ftps", 0.1, 30.0, "ft/s");
  b.wheel_base_in = base.Get<double>("wheel_base_in", 4.0, 60.0, "in");
  base.Finish();

  robot.Finish();
  return cfg;
}

RobotConfig LoadRobotConfigFile(const std::string& path) {
  const StrictYaml root = StrictYaml::LoadFile(path);
  RobotConfig cfg = LoadRobotConfig(root);
  root.Finish();
  return cfg;
}

std::string DefaultRobotConfigPath() {
  return DefaultConfigDir() + "/robot.yaml";
}

}  // namespace stickrep::sensing
