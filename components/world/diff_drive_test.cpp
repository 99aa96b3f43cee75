#include "world/diff_drive.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "common/units.h"

namespace stickrep::world {
namespace {

using ::testing::DoubleNear;

BaseModel NoSlip() {
  BaseModel model;
  model.slip_stddev = 0.0;
  return model;
}

TEST(DiffDriveTest, StraightLineAdvancesSpeedTimesTime) {
  DiffDriveBase base(NoSlip(), {0.0, 0.0, 0.0});
  std::mt19937_64 rng(1);
  for (int i = 0; i < 10; ++i) base.Step(2.0, 0.0, 0.1, rng);
  EXPECT_THAT(base.true_pose().x_in, DoubleNear(24.0, 1e-9));
  EXPECT_THAT(base.true_pose().y_in, DoubleNear(0.0, 1e-9));
  EXPECT_THAT(base.odometry_distance_in(), DoubleNear(24.0, 1e-9));
}

TEST(DiffDriveTest, TurnInPlaceChangesHeadingOnly) {
  DiffDriveBase base(NoSlip(), {10.0, 5.0, 0.0});
  std::mt19937_64 rng(1);
  base.Step(0.0, kPi / 2.0, 1.0, rng);
  EXPECT_THAT(base.true_pose().theta_rad, DoubleNear(kPi / 2.0, 1e-9));
  EXPECT_THAT(base.true_pose().x_in, DoubleNear(10.0, 1e-9));
  EXPECT_THAT(base.true_pose().y_in, DoubleNear(5.0, 1e-9));
}

TEST(DiffDriveTest, ArcEndsOnTheCircleOfCommandedRadius) {
  // 1 ft/s at 0.1 rad/s: radius 120 in; a quarter turn ends at (120, 120).
  DiffDriveBase base(NoSlip(), {0.0, 0.0, 0.0});
  std::mt19937_64 rng(1);
  base.Step(1.0, 0.1, kPi / 2.0 / 0.1, rng);
  EXPECT_THAT(base.true_pose().x_in, DoubleNear(120.0, 1e-6));
  EXPECT_THAT(base.true_pose().y_in, DoubleNear(120.0, 1e-6));
}

TEST(DiffDriveTest, SpeedIsLimitedToTheRatedTopSpeed) {
  DiffDriveBase base(NoSlip(), {0.0, 0.0, 0.0});
  std::mt19937_64 rng(1);
  base.Step(5.0, 0.0, 1.0, rng);
  EXPECT_THAT(base.last_speed_ftps(), DoubleNear(2.6, 1e-12));
  EXPECT_THAT(base.true_pose().x_in, DoubleNear(31.2, 1e-9));
}

TEST(DiffDriveTest, SpeedLimitKeepsTheCommandedCurvature) {
  DiffDriveBase base(NoSlip(), {0.0, 0.0, 0.0});
  std::mt19937_64 rng(1);
  const WheelTravel travel = base.Step(5.0, 0.5, 0.1, rng);  // radius 120 in
  const double radius =
      14.0 / 2.0 * (travel.right_in + travel.left_in) / (travel.right_in - travel.left_in);
  EXPECT_THAT(radius, DoubleNear(120.0, 1e-9));
  EXPECT_LE(std::max(travel.left_in, travel.right_in), 31.2 * 0.1 + 1e-9);
}

TEST(DiffDriveTest, WheelSlipMakesTruthDepartFromOdometryReproducibly) {
  BaseModel model;
  model.slip_stddev = 0.02;
  auto run = [&](std::uint64_t seed) {
    DiffDriveBase base(model, {0.0, 0.0, 0.0});
    std::mt19937_64 rng(seed);
    for (int i = 0; i < 50; ++i) base.Step(2.6, 0.0, 0.2, rng);
    return base;
  };
  const DiffDriveBase a = run(42);
  const DiffDriveBase b = run(42);
  EXPECT_THAT(a.odometry_pose().x_in, DoubleNear(31.2 * 10.0, 1e-9));
  EXPECT_NE(a.true_pose().x_in, a.odometry_pose().x_in);
  EXPECT_NE(a.true_pose().y_in, 0.0);
  EXPECT_DOUBLE_EQ(a.true_pose().x_in, b.true_pose().x_in);
  EXPECT_DOUBLE_EQ(a.true_pose().y_in, b.true_pose().y_in);
}

TEST(DiffDriveTest, NonFiniteCommandStopsTheBase) {
  DiffDriveBase base(NoSlip(), {1.0, 2.0, 0.3});
  std::mt19937_64 rng(1);
  base.Step(std::numeric_limits<double>::quiet_NaN(), 0.0, 0.1, rng);
  base.Step(1.0, 0.0, -0.1, rng);
  EXPECT_DOUBLE_EQ(base.true_pose().x_in, 1.0);
  EXPECT_DOUBLE_EQ(base.true_pose().theta_rad, 0.3);
  EXPECT_DOUBLE_EQ(base.last_speed_ftps(), 0.0);
}

}  // namespace
}  // namespace stickrep::world
