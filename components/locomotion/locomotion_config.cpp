#include "locomotion/locomotion_config.h"

#include <algorithm>
#include <initializer_list>

#include "common/units.h"
#include "stickrep/map.h"

namespace stickrep::locomotion {

namespace {

// The first of `keys` that `h` gives, else the first: the key a check between keys names.
const char* GivenKey(const StrictYaml& h, std::initializer_list<const char*> keys) {
  for (const char* key : keys) {
    if (h.Has(key)) return key;
  }
  return *keys.begin();
}

// The hallway keys of `h` into `b`: every one required, or (a floor's own block) only those
// given, over the values `b` holds; the keys' bounds and the checks between them either way.
void LoadHallway(const StrictYaml& h, bool every_key, HallwayBehaviourConfig& b) {
  const auto read = [&](const char* key, double lo, double hi, const char* unit, double& to) {
    if (every_key || h.Has(key)) to = h.Get<double>(key, lo, hi, unit);
  };
  HallwayFollowerConfig& f = b.follower;
  read("length_scale_in", 6.0, 240.0, "in", f.length_scale_in);
  read("max_correction_heading_deg", 0.5, 30.0, "deg", f.max_correction_heading_deg);
  read("stop_distance_in", 12.0, 120.0, "in", f.stop_distance_in);
  read("swept_clearance_in", 0.0, 36.0, "in", f.swept_clearance_in);
  read("max_accel_ftps2", 0.1, 10.0, "ft/s^2", f.max_accel_ftps2);
  read("brake_decel_ftps2", 0.1, 10.0, "ft/s^2", f.brake_decel_ftps2);
  read("turn_rate_radps", 0.05, 3.0, "rad/s", b.turn_rate_radps);
  read("scan_timeout_s", 0.1, 5.0, "s", b.scan_timeout_s);
  read("envelope_offset_in", 1.0, 60.0, "in", b.envelope_offset_in);
  read("envelope_heading_deg", 0.5, 30.0, "deg", b.envelope_heading_deg);
  if (every_key || h.Has("frames_per_door")) {
    b.frames_per_door = h.Get<int>("frames_per_door", 0, 20, "frames");
  }
  read("min_view_speed_ftps", 0.1, 5.0, "ft/s", b.min_view_speed_ftps);
  read("max_view_offset_in", 0.0, 60.0, "in", b.max_view_offset_in);
  if (b.max_view_offset_in >= b.envelope_offset_in) {
    h.Fail(GivenKey(h, {"max_view_offset_in", "envelope_offset_in"}),
           "max_view_offset_in must be less than envelope_offset_in");
  }
  read("view_offset_after_in", 0.0, 1200.0, "in", b.view_offset_after_in);
  read("stall_speed_ftps", 0.05, 5.0, "ft/s", b.stall_speed_ftps);
  read("stall_time_s", 0.1, 10.0, "s", b.stall_time_s);
  read("stall_travel_in", 0.01, 12.0, "in", b.stall_travel_in);
  if (b.stall_travel_in >= FeetToInches(b.stall_speed_ftps) * b.stall_time_s) {
    h.Fail(GivenKey(h, {"stall_travel_in", "stall_time_s", "stall_speed_ftps"}),
           "stall_travel_in must be less than stall_time_s at stall_speed_ftps travels");
  }
  h.Finish();
}

}  // namespace

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
  LoadHallway(c.Child("hallway"), /*every_key=*/true, out.behaviour);
  out.behaviour.follower.max_angular_radps =
      std::min(out.behaviour.follower.max_angular_radps, out.limits.max_angular_rate_radps);
  if (c.Has("on_maps")) {
    const StrictYaml maps = c.Child("on_maps");
    for (const std::string& name : maps.Keys()) {
      HallwayBehaviourConfig& own = out.on_maps[name] = out.behaviour;
      LoadHallway(maps.Child(name), /*every_key=*/false, own);
    }
    maps.Finish();
  }
  c.Finish();
  return out;
}

LocomotionConfig ForMap(LocomotionConfig config, const std::string& map_name) {
  const auto own = config.on_maps.find(map_name);
  if (own != config.on_maps.end()) config.behaviour = own->second;
  config.on_maps.clear();
  return config;
}

}  // namespace stickrep::locomotion
