#include "locomotion/locomotion_config.h"

#include <algorithm>

#include "common/units.h"
#include "stickrep/map.h"

namespace stickrep::locomotion {

void ApplyRobot(const sensing::RobotConfig& robot, HallwayBehaviourConfig& behaviour) {
  HallwayFollowerConfig& f = behaviour.follower;
  f.sensor_count = robot.sonar_ring.count;
  f.spacing_deg = robot.sonar_ring.spacing_deg;
  f.head_radius_in = robot.sonar_ring.head_radius_in;
  f.cone_deg = robot.sonar_ring.cone_deg;
  f.coaxial_sensor = robot.camera.coaxial_sensor;
  f.max_speed_ftps = robot.base.max_speed_ftps;
  behaviour.camera_fov_deg = robot.camera.fov_deg;
  behaviour.camera_frame_period_s = 1.0 / robot.camera.frame_rate_hz;
  behaviour.door_in_view_in = map::DoorClassWidthIn(map::DoorClass::k40);
}

LocomotionConfig LoadLocomotionConfig(const StrictYaml& c, const sensing::RobotConfig& robot) {
  LocomotionConfig out;
  out.device = c.Get<std::string>("device");
  if (out.device == "serial") {
    c.Fail("device", "the LabMate serial driver is not built yet; use 'virtual'");
  } else if (out.device != "virtual") {
    c.Fail("device", "'" + out.device + "' is not one of: virtual, serial");
  }
  out.resend_rate_hz = c.Get<double>("control_rate_hz", 1.0, 200.0, "Hz");
  out.command_timeout_s = c.Get<double>("command_timeout_s", 0.05, 5.0, "s");
  out.limits.max_angular_rate_radps = c.Get<double>("max_angular_rate_radps", 0.01, 5.0, "rad/s");
  out.limits.max_speed_ftps = robot.base.max_speed_ftps;
  out.limits.wheel_base_in = robot.base.wheel_base_in;

  ApplyRobot(robot, out.behaviour);
  const StrictYaml h = c.Child("hallway");
  HallwayFollowerConfig& f = out.behaviour.follower;
  f.length_scale_in = h.Get<double>("length_scale_in", 6.0, 240.0, "in");
  f.max_correction_heading_deg = h.Get<double>("max_correction_heading_deg", 0.5, 30.0, "deg");
  f.stop_distance_in = h.Get<double>("stop_distance_in", 12.0, 120.0, "in");
  f.swept_clearance_in = h.Get<double>("swept_clearance_in", 0.0, 36.0, "in");
  f.max_accel_ftps2 = h.Get<double>("max_accel_ftps2", 0.1, 10.0, "ft/s^2");
  f.brake_decel_ftps2 = h.Get<double>("brake_decel_ftps2", 0.1, 10.0, "ft/s^2");
  out.behaviour.turn_rate_radps = h.Get<double>("turn_rate_radps", 0.05, 3.0, "rad/s");
  out.behaviour.scan_timeout_s = h.Get<double>("scan_timeout_s", 0.1, 5.0, "s");
  out.behaviour.envelope_offset_in = h.Get<double>("envelope_offset_in", 1.0, 60.0, "in");
  out.behaviour.envelope_heading_deg = h.Get<double>("envelope_heading_deg", 0.5, 30.0, "deg");
  out.behaviour.frames_per_door = h.Get<int>("frames_per_door", 0, 20, "frames");
  out.behaviour.min_view_speed_ftps = h.Get<double>("min_view_speed_ftps", 0.1, 5.0, "ft/s");
  out.behaviour.max_view_offset_in = h.Get<double>("max_view_offset_in", 0.0, 60.0, "in");
  if (out.behaviour.max_view_offset_in >= out.behaviour.envelope_offset_in) {
    h.Fail("max_view_offset_in", "must be less than envelope_offset_in");
  }
  out.behaviour.view_offset_after_in = h.Get<double>("view_offset_after_in", 0.0, 1200.0, "in");
  out.behaviour.stall_speed_ftps = h.Get<double>("stall_speed_ftps", 0.05, 5.0, "ft/s");
  out.behaviour.stall_time_s = h.Get<double>("stall_time_s", 0.1, 10.0, "s");
  out.behaviour.stall_travel_in = h.Get<double>("stall_travel_in", 0.01, 12.0, "in");
  if (out.behaviour.stall_travel_in >=
      FeetToInches(out.behaviour.stall_speed_ftps) * out.behaviour.stall_time_s) {
    h.Fail("stall_travel_in", "must be less than stall_time_s at stall_speed_ftps travels");
  }
  h.Finish();
  f.max_angular_radps = std::min(f.max_angular_radps, out.limits.max_angular_rate_radps);
  c.Finish();
  return out;
}

}  // namespace stickrep::locomotion
