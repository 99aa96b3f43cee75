#include "locomotion/drive.h"

#include <algorithm>
#include <cmath>

#include "common/units.h"

namespace stickrep::locomotion {

void Odometer::Update(double left_travel_in, double right_travel_in) {
  if (!initialised_) {
    initialised_ = true;
    last_left_in_ = left_travel_in;
    last_right_in_ = right_travel_in;
    return;
  }
  const double dl = left_travel_in - last_left_in_;
  const double dr = right_travel_in - last_right_in_;
  last_left_in_ = left_travel_in;
  last_right_in_ = right_travel_in;
  const double ds = 0.5 * (dl + dr);
  const double dtheta = (dr - dl) / wheel_base_in_;
  // Integrate along the arc's mid heading (second-order accurate for small steps).
  const double mid = pose_.heading_rad + 0.5 * dtheta;
  pose_.x_in += ds * std::cos(mid);
  pose_.y_in += ds * std::sin(mid);
  pose_.heading_rad = std::remainder(pose_.heading_rad + dtheta, 2.0 * kPi);
  distance_in_ += ds;
}

WheelSpeeds ToWheelSpeeds(double linear_ftps, double angular_radps, const DriveLimits& limits) {
  if (!std::isfinite(linear_ftps) || !std::isfinite(angular_radps)) return {};
  const double v = std::clamp(linear_ftps, -limits.max_speed_ftps, limits.max_speed_ftps);
  const double w = std::clamp(angular_radps, -limits.max_angular_rate_radps,
                              limits.max_angular_rate_radps);
  const double half_track_ft = InchesToFeet(limits.wheel_base_in) / 2.0;
  double left = v - w * half_track_ft;
  double right = v + w * half_track_ft;
  const double peak = std::max(std::abs(left), std::abs(right));
  if (peak > limits.max_speed_ftps) {
    left *= limits.max_speed_ftps / peak;
    right *= limits.max_speed_ftps / peak;
  }
  return {left, right};
}

}  // namespace stickrep::locomotion
