#pragma once

#include <string>

#include "common/strict_yaml.h"

namespace stickrep::sensing {

// The sonar ring of the robot head (§4.3, §5.4): 24 Polaroid transducers every 15°.
// Sensor k points along bearing (k - camera.coaxial_sensor) * spacing measured from the
// optical axis, positive toward increasing image columns (the image's right).
struct SonarRingConfig {
  int count = 24;               // §5.3: "the 24 sensors"
  double spacing_deg = 15.0;    // §5.3: "sectors of 15°"
  double head_radius_in = 7.5;  // not in the text; see configs/robot.yaml
  double cone_deg = 23.6;       // §5.4: "the 23.6° sensing cone"
  double min_range_in = 12.0;   // §4.3: "useful measuring range of 1 to 35 feet"
  double max_range_in = 420.0;  // 35 ft
  double footprint_deg = 15.0;  // §4.3: accurate ranging footprint, phi <= 15°

  // Throws InputError (file/line/key taken from `where`) when a value is inconsistent.
  void Validate(const StrictYaml& where) const;
};

// The monochrome camera (§4.1, §5.2, constraint C7: focal length and field of view known).
struct CameraConfig {
  double fov_deg = 55.817;           // §5.4: "field of view of 55.817°"
  int image_width_px = 512;          // not in the text; see configs/robot.yaml
  int image_height_px = 480;         // not in the text
  double focal_length_mm = 6.0;      // §4.1.1: "the 6mm lens"
  double pixel_pitch_mm = 0.012414;  // derived: f * tan(FOV/2) / (width/2)
  int coaxial_sensor = 0;            // the sonar sensor whose axis is the optical axis (C3)
  double offset_forward_in = 0.0;    // camera centre ahead of the ring centre, on the axis
  // The lens's radial distortion from calibration: x_d = x_u (1 + k1 r_u^2) in normalised
  // image coordinates (k1 > 0: pincushion). The renderer draws with it; the sensing undoes it.
  double radial_distortion_k1 = 0.10;  // configs/robot.yaml
  double frame_rate_hz = 5.0;          // §6.3: "a frame every 0.2 seconds"

  // The pitch, focal length, width and FOV are not independent: the image edge must sit at
  // FOV/2. Rejects sets that disagree by more than 0.5°.
  void Validate(const StrictYaml& where, const SonarRingConfig& ring) const;
};

// The mobile base (§6.3: a TRC LabMate, rated 2.6 ft/s).
struct BaseConfig {
  double max_speed_ftps = 2.6;  // §6.3: "maximum Labmate base speed of 2.6 feet per second"
  double wheel_base_in = 14.0;  // not in the text; see configs/robot.yaml
};

// The physical robot: one file, configs/robot.yaml, read by every process that needs the
// geometry (sonar, camera, locomotion, landmark, virtual robot).
struct RobotConfig {
  SonarRingConfig sonar_ring;
  CameraConfig camera;
  BaseConfig base;
};

// Reads the `robot:` mapping of `root` (every key required, unknown keys rejected) and
// validates it. Throws InputError naming file, line and key.
RobotConfig LoadRobotConfig(const StrictYaml& root);

// Loads `path` (a file holding only `robot:`, like configs/robot.yaml) and validates it.
RobotConfig LoadRobotConfigFile(const std::string& path);

// Path of the shipped file, configs/robot.yaml in the source tree.
std::string DefaultRobotConfigPath();

}  // namespace stickrep::sensing
