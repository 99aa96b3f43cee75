#pragma once

#include <cstdint>

namespace stickrep::locomotion {

// Planar pose in the odometry frame: inches and radians (CCW from the start heading).
struct Pose2 {
  double x_in = 0.0;
  double y_in = 0.0;
  double heading_rad = 0.0;
};

// Dead reckoning of a differential-drive base from cumulative wheel travel.
class Odometer {
 public:
  explicit Odometer(double wheel_base_in) : wheel_base_in_(wheel_base_in) {}
  // Feeds the encoders' cumulative travel; the first call only sets the reference.
  void Update(double left_travel_in, double right_travel_in);
  const Pose2& pose() const { return pose_; }
  // Odometer reading: path length of the base centre along its forward axis since the first
  // reading, backward travel counting negative. The robot travels a hallway forward or
  // backward with the camera facing the wall (§6.3), so this is the along-wall coordinate
  // that the landmark and localizer processes place doors with.
  double distance_in() const { return distance_in_; }

 private:
  double wheel_base_in_;
  bool initialised_ = false;
  double last_left_in_ = 0.0, last_right_in_ = 0.0;
  Pose2 pose_;
  double distance_in_ = 0.0;
};

struct WheelSpeeds {
  double left_ftps = 0.0;
  double right_ftps = 0.0;
};

// Limits the base obeys whatever it is told.
struct DriveLimits {
  double max_speed_ftps = 2.6;          // the LabMate's rated top speed (§6.3)
  double max_angular_rate_radps = 1.0;
  double wheel_base_in = 14.0;
};

// Turns a linear and angular set-point into wheel speeds: the linear speed is clamped to the
// base's top speed and the turn rate to its limit, then scaled together so that neither
// wheel exceeds the top speed. Non-finite set-points give a stop.
WheelSpeeds ToWheelSpeeds(double linear_ftps, double angular_radps, const DriveLimits& limits);

}  // namespace stickrep::locomotion
