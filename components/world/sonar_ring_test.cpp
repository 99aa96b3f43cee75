#include "world/sonar_ring.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "common/units.h"

namespace stickrep::world {
namespace {

using ::testing::DoubleNear;
using ::testing::SizeIs;

// A wide straight hallway: the feature wall at y = +60, the plain wall at y = -60.
Scene WideHallway() {
  HallwayOptions options;
  options.width_in = 120.0;
  return Scene(MakeStraightHallway({HallwayFeature::Wall(600)}, options));
}

TEST(SonarRingTest, SensorBearingsStepClockwiseFromTheCoaxialSensor) {
  const SonarRingSimulator ring;
  const Pose2d X_WR{0.0, 0.0, 0.0};
  EXPECT_THAT(ring.SensorBearing(X_WR, 0), DoubleNear(DegToRad(90.0), 1e-12));
  EXPECT_THAT(ring.SensorBearing(X_WR, 1), DoubleNear(DegToRad(75.0), 1e-12));
  EXPECT_THAT(ring.SensorBearing(X_WR, 6), DoubleNear(0.0, 1e-12));
}

TEST(SonarRingTest, CoaxialSensorFacingWallReadsPerpendicularDistanceFromItsFace) {
  const SonarRingSimulator ring;
  const auto readings = ring.SenseExact(WideHallway(), {300.0, 0.0, 0.0});
  ASSERT_THAT(readings, SizeIs(24));
  ASSERT_TRUE(readings[0].valid);
  EXPECT_THAT(readings[0].range_in, DoubleNear(60.0 - 7.5, 1e-9));
  EXPECT_THAT(readings[0].incidence_rad, DoubleNear(0.0, 1e-9));
}

TEST(SonarRingTest, OppositeSensorReadsTheOtherWall) {
  const SonarRingSimulator ring;
  const auto readings = ring.SenseExact(WideHallway(), {300.0, 10.0, 0.0});
  ASSERT_TRUE(readings[12].valid);  // 180° from sensor 0
  EXPECT_THAT(readings[12].range_in, DoubleNear(70.0 - 7.5, 1e-9));
}

TEST(SonarRingTest, SensorWithNormalOutsideItsConeReadsAlongTheConeLimit) {
  // Sensor 1 looks 15° off the wall normal; the 23.6° cone reaches 11.8° from its axis,
  // so the nearest point lies on the cone edge 3.2° from the normal (§5.4.1, Case 2).
  const SonarRingSimulator ring;
  const auto readings = ring.SenseExact(WideHallway(), {300.0, 0.0, 0.0});
  ASSERT_TRUE(readings[1].valid);
  const double face_to_wall = 60.0 - 7.5 * std::cos(DegToRad(15.0));
  EXPECT_THAT(readings[1].true_range_in,
              DoubleNear(face_to_wall / std::cos(DegToRad(15.0 - 11.8)), 1e-9));
  EXPECT_THAT(readings[1].incidence_rad, DoubleNear(DegToRad(15.0), 1e-9));
}

TEST(SonarRingTest, SensorLookingDownTheHallwaySeesTheSideWallAtItsConeLimit) {
  // Bearing 0, along the 120 in hallway: the cone edge meets the wall 60 in to the side.
  const SonarRingSimulator ring;
  const auto readings = ring.SenseExact(WideHallway(), {300.0, 0.0, 0.0});
  ASSERT_TRUE(readings[6].valid);
  EXPECT_THAT(readings[6].true_range_in, DoubleNear(60.0 / std::sin(DegToRad(11.8)), 1e-9));
  EXPECT_THAT(readings[6].incidence_rad, DoubleNear(DegToRad(90.0), 1e-9));
}

TEST(SonarRingTest, SensorWithNothingInItsConeWithinMaxRangeIsInvalid) {
  // In a 20 ft hallway the 11.8° cone edge meets a side wall 587 in away, past 35 ft.
  HallwayOptions options;
  options.width_in = 240.0;
  const Scene scene(MakeStraightHallway({HallwayFeature::Wall(600)}, options));
  const auto readings = SonarRingSimulator().SenseExact(scene, {300.0, 0.0, 0.0});
  EXPECT_FALSE(readings[6].valid);
  EXPECT_FALSE(readings[18].valid);
}

// Adds 10 % and remembers what it was asked, to check the hook's arguments.
class TenPercentLong final : public SonarErrorModel {
 public:
  std::optional<double> Apply(double true_range_in, SurfaceType surface, double incidence_rad,
                              std::mt19937_64&) const override {
    last_surface = surface;
    last_incidence = incidence_rad;
    return true_range_in * 1.1;
  }
  mutable SurfaceType last_surface = SurfaceType::kConcrete;
  mutable double last_incidence = -1.0;
};

TEST(SonarRingTest, ErrorModelReceivesSurfaceAndIncidenceAndSetsTheRange) {
  HallwayOptions options;
  options.width_in = 120.0;
  options.feature_surface = SurfaceType::kCloth;
  const Scene scene(MakeStraightHallway({HallwayFeature::Wall(600)}, options));
  const SonarRingSimulator ring;
  TenPercentLong model;
  std::mt19937_64 rng(7);
  const auto readings = ring.Sense(scene, {300.0, 0.0, 0.0}, model, rng);
  EXPECT_THAT(readings[0].range_in, DoubleNear(52.5 * 1.1, 1e-9));
  EXPECT_THAT(readings[0].true_range_in, DoubleNear(52.5, 1e-9));
  EXPECT_EQ(readings[0].surface, SurfaceType::kCloth);
}

TEST(SonarRingTest, ReadingBelowMinimumRangeIsInvalid) {
  const SonarRingSimulator ring;
  // The transducer face is 60 - 50 - 7.5 = 2.5 in from the wall: under the 12 in minimum.
  const auto readings = ring.SenseExact(WideHallway(), {300.0, 50.0, 0.0});
  EXPECT_FALSE(readings[0].valid);
  EXPECT_THAT(readings[0].true_range_in, DoubleNear(2.5, 1e-9));
}

}  // namespace
}  // namespace stickrep::world
