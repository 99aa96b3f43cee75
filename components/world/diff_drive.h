#pragma once

#include <random>

#include "world/world.h"

namespace stickrep::world {

// The mobile base. Defaults follow configs/robot.yaml (`robot.base`).
struct BaseModel {
  double max_speed_ftps = 2.6;  // §6.3: "maximum Labmate base speed of 2.6 feet per second"
  double wheel_base_in = 14.0;  // not in the text; configs/robot.yaml placeholder
  // Wheel slip: each wheel's true travel over a step is its encoder travel times
  // (1 + scale_error + N(0, slip_stddev)). Not measured in the text (which only speaks of
  // "wheel error", §6.3); 1 % per-step noise and no bias by default.
  double slip_stddev = 0.01;
  double left_scale_error = 0.0;
  double right_scale_error = 0.0;
};

// Encoder travel of one step, as the locomotion process would read it.
struct WheelTravel {
  double left_in = 0.0;
  double right_in = 0.0;
};

// Differential-drive kinematics with wheel slip. Keeps two poses: the true pose (what the
// world sees) and the odometry pose integrated from the encoders (what the robot believes).
// Commands are body speeds; each wheel is limited to the rated top speed, scaling both
// wheels together so the commanded curvature is kept.
class DiffDriveBase {
 public:
  // Throws std::invalid_argument on a non-positive wheel base or speed limit.
  DiffDriveBase(BaseModel model, Pose2d X_WR_start);

  // Advances dt_s seconds under the command. Returns the encoder travel of the step.
  // Non-finite commands or dt are treated as a stop (never a crash).
  WheelTravel Step(double speed_ftps, double turn_rate_radps, double dt_s, std::mt19937_64& rng);

  const BaseModel& model() const { return model_; }
  const Pose2d& true_pose() const { return X_WR_true_; }
  const Pose2d& odometry_pose() const { return X_WR_odom_; }
  double odometry_distance_in() const { return odom_distance_in_; }
  double true_distance_in() const { return true_distance_in_; }
  // The body speed actually applied by the last step after limiting, in ft/s.
  double last_speed_ftps() const { return last_speed_ftps_; }

  void Reset(const Pose2d& X_WR);

 private:
  BaseModel model_;
  Pose2d X_WR_true_;
  Pose2d X_WR_odom_;
  double odom_distance_in_ = 0.0;
  double true_distance_in_ = 0.0;
  double last_speed_ftps_ = 0.0;
};

// Integrates a pose along an arc of wheel travels (exact for constant wheel speeds).
Pose2d IntegrateWheels(const Pose2d& X_WR, double left_in, double right_in, double wheel_base_in);

}  // namespace stickrep::world
