#include "world/diff_drive.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/units.h"

namespace stickrep::world {

Pose2d IntegrateWheels(const Pose2d& X_WR, double left_in, double right_in, double wheel_base_in) {
  const double ds = (left_in + right_in) / 2.0;
  const double dtheta = (right_in - left_in) / wheel_base_in;
  Pose2d out = X_WR;
  if (std::abs(dtheta) < 1e-12) {
    out.x_in += ds * std::cos(X_WR.theta_rad);
    out.y_in += ds * std::sin(X_WR.theta_rad);
  } else {
    // Arc of radius ds / dtheta about the instantaneous centre of rotation.
    const double radius = ds / dtheta;
    out.x_in += radius * (std::sin(X_WR.theta_rad + dtheta) - std::sin(X_WR.theta_rad));
    out.y_in -= radius * (std::cos(X_WR.theta_rad + dtheta) - std::cos(X_WR.theta_rad));
  }
  out.theta_rad = std::remainder(X_WR.theta_rad + dtheta, 2.0 * kPi);
  return out;
}

DiffDriveBase::DiffDriveBase(BaseModel model, Pose2d X_WR_start)
    : model_(model), X_WR_true_(X_WR_start), X_WR_odom_(X_WR_start) {
  if (!(model_.wheel_base_in > 0.0) || !(model_.max_speed_ftps > 0.0) ||
      !(model_.slip_stddev >= 0.0)) {
    throw std::invalid_argument(
        "base: wheel_base_in and max_speed_ftps must be > 0, slip_stddev >= 0");
  }
}

void DiffDriveBase::Reset(const Pose2d& X_WR) {
  X_WR_true_ = X_WR;
  X_WR_odom_ = X_WR;
  odom_distance_in_ = 0.0;
  true_distance_in_ = 0.0;
  last_speed_ftps_ = 0.0;
}

WheelTravel DiffDriveBase::Step(double speed_ftps, double turn_rate_radps, double dt_s,
                                std::mt19937_64& rng) {
  if (!std::isfinite(speed_ftps) || !std::isfinite(turn_rate_radps) || !std::isfinite(dt_s) ||
      dt_s <= 0.0) {
    last_speed_ftps_ = 0.0;
    return {};
  }
  const double v_inps = FeetToInches(speed_ftps);
  const double half_track = model_.wheel_base_in / 2.0;
  double v_left = v_inps - turn_rate_radps * half_track;
  double v_right = v_inps + turn_rate_radps * half_track;
  // Each wheel is rated to the base's top speed; scaling both keeps the path's curvature.
  const double limit = FeetToInches(model_.max_speed_ftps);
  const double peak = std::max(std::abs(v_left), std::abs(v_right));
  if (peak > limit) {
    v_left *= limit / peak;
    v_right *= limit / peak;
  }
  last_speed_ftps_ = InchesToFeet((v_left + v_right) / 2.0);

  WheelTravel encoder{v_left * dt_s, v_right * dt_s};
  std::normal_distribution<double> slip(0.0, model_.slip_stddev);
  const double sl = model_.slip_stddev > 0.0 ? slip(rng) : 0.0;
  const double sr = model_.slip_stddev > 0.0 ? slip(rng) : 0.0;
  const double true_left = encoder.left_in * (1.0 + model_.left_scale_error + sl);
  const double true_right = encoder.right_in * (1.0 + model_.right_scale_error + sr);

  X_WR_odom_ = IntegrateWheels(X_WR_odom_, encoder.left_in, encoder.right_in, model_.wheel_base_in);
  X_WR_true_ = IntegrateWheels(X_WR_true_, true_left, true_right, model_.wheel_base_in);
  odom_distance_in_ += std::abs(encoder.left_in + encoder.right_in) / 2.0;
  true_distance_in_ += std::abs(true_left + true_right) / 2.0;
  return encoder;
}

}  // namespace stickrep::world
