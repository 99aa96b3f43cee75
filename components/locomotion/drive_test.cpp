#include "locomotion/drive.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/units.h"

namespace stickrep::locomotion {
namespace {

using ::testing::DoubleNear;

TEST(OdometerTest, EqualWheelTravelGoesStraight) {
  Odometer odo(14.0);
  odo.Update(0.0, 0.0);
  odo.Update(120.0, 120.0);
  EXPECT_THAT(odo.pose().x_in, DoubleNear(120.0, 1e-9));
  EXPECT_THAT(odo.pose().y_in, DoubleNear(0.0, 1e-9));
  EXPECT_THAT(odo.distance_in(), DoubleNear(120.0, 1e-9));
}

TEST(OdometerTest, OppositeWheelTravelTurnsInPlace) {
  Odometer odo(14.0);
  odo.Update(0.0, 0.0);
  const double quarter_turn_in = kPi / 2.0 * 7.0;  // arc of each wheel for 90 deg
  for (int i = 1; i <= 100; ++i) odo.Update(-quarter_turn_in * i / 100, quarter_turn_in * i / 100);
  EXPECT_THAT(odo.pose().heading_rad, DoubleNear(kPi / 2.0, 1e-9));
  EXPECT_THAT(odo.pose().x_in, DoubleNear(0.0, 1e-9));
}

TEST(OdometerTest, QuarterCircleEndsWhereGeometrySays) {
  Odometer odo(14.0);
  odo.Update(0.0, 0.0);
  const double radius_in = 60.0;
  const int steps = 1000;
  for (int i = 1; i <= steps; ++i) {
    const double a = kPi / 2.0 * i / steps;
    odo.Update((radius_in - 7.0) * a, (radius_in + 7.0) * a);
  }
  EXPECT_THAT(odo.pose().x_in, DoubleNear(radius_in, 1e-3));
  EXPECT_THAT(odo.pose().y_in, DoubleNear(radius_in, 1e-3));
}

TEST(WheelSpeedsTest, LinearSpeedIsClampedToTheBaseTopSpeed) {
  const WheelSpeeds s = ToWheelSpeeds(10.0, 0.0, DriveLimits{});
  EXPECT_DOUBLE_EQ(s.left_ftps, 2.6);
  EXPECT_DOUBLE_EQ(s.right_ftps, 2.6);
}

TEST(WheelSpeedsTest, TurningAtTopSpeedKeepsBothWheelsWithinTheLimit) {
  const WheelSpeeds s = ToWheelSpeeds(2.6, 1.0, DriveLimits{});
  EXPECT_LE(std::abs(s.left_ftps), 2.6 + 1e-12);
  EXPECT_LE(std::abs(s.right_ftps), 2.6 + 1e-12);
  EXPECT_GT(s.right_ftps, s.left_ftps);
}

TEST(WheelSpeedsTest, NanSetPointStopsTheBase) {
  const WheelSpeeds s = ToWheelSpeeds(std::numeric_limits<double>::quiet_NaN(), 0.0, DriveLimits{});
  EXPECT_EQ(s.left_ftps, 0.0);
  EXPECT_EQ(s.right_ftps, 0.0);
}

}  // namespace
}  // namespace stickrep::locomotion
