#include "world/scene.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "common/units.h"
#include "world/world.h"

namespace stickrep::world {
namespace {

using ::testing::DoubleNear;
using ::testing::SizeIs;

// A 72 in wide hallway: 120 in of wall, a 36 in door, 120 in of wall on the y = +36 side.
World DoorHallway(DoorState state = DoorState::kClosed, double angle_rad = 0.0) {
  return MakeStraightHallway({HallwayFeature::Wall(120), HallwayFeature::Door(36, state, angle_rad),
                              HallwayFeature::Wall(120)});
}

TEST(MakeStraightHallwayTest, LaysDoorsAtTheirCumulativeOffsets) {
  const World world = MakeStraightHallway({HallwayFeature::Wall(100), HallwayFeature::Door(32),
                                           HallwayFeature::Wall(50), HallwayFeature::Door(72)});
  ASSERT_THAT(world.doors, SizeIs(2));
  EXPECT_DOUBLE_EQ(world.doors[0].offset_in, 100.0);
  EXPECT_DOUBLE_EQ(world.doors[0].width_in, 32.0);
  EXPECT_FALSE(world.doors[0].double_door);
  EXPECT_DOUBLE_EQ(world.doors[1].offset_in, 182.0);
  EXPECT_TRUE(world.doors[1].double_door);
  EXPECT_DOUBLE_EQ(world.walls[0].b_in.x(), 254.0);
}

TEST(MakeStraightHallwayTest, RejectsNonPositiveLength) {
  EXPECT_THROW(MakeStraightHallway({HallwayFeature::Wall(0.0)}), std::invalid_argument);
}

TEST(DoorClassTest, MapsLegalWidthsAndRejectsOthers) {
  EXPECT_EQ(DoorClassForWidth(36.2), 36);
  EXPECT_EQ(DoorClassForWidth(60.0), 60);
  EXPECT_EQ(DoorClassForWidth(34.0), std::nullopt);
}

TEST(SceneTest, RejectsDoorThatDoesNotFitOnItsWall) {
  World world = DoorHallway();
  world.doors[0].offset_in = 250.0;
  EXPECT_THROW(Scene{world}, std::invalid_argument);
}

TEST(SceneTest, RaycastAtNormalIncidenceReturnsPerpendicularDistance) {
  const Scene scene(DoorHallway());
  const auto hit = scene.Raycast({50.0, 0.0}, {0.0, 1.0}, 1000.0, 30.0);
  ASSERT_TRUE(hit.has_value());
  EXPECT_THAT(hit->distance_in, DoubleNear(36.0, 1e-9));
  EXPECT_THAT(hit->incidence_rad, DoubleNear(0.0, 1e-9));
  EXPECT_EQ(hit->surface, SurfaceType::kConcrete);
}

TEST(SceneTest, RaycastAtObliqueAngleReturnsSlantRangeAndIncidence) {
  const Scene scene(DoorHallway());
  const double angle = DegToRad(30.0);
  const auto hit = scene.Raycast({50.0, 0.0}, {std::sin(angle), std::cos(angle)}, 1000.0, 30.0);
  ASSERT_TRUE(hit.has_value());
  EXPECT_THAT(hit->distance_in, DoubleNear(36.0 / std::cos(angle), 1e-9));
  EXPECT_THAT(hit->incidence_rad, DoubleNear(angle, 1e-9));
}

TEST(SceneTest, RaycastHitsClosedLeafRecessedBehindTheWallFace) {
  const Scene scene(DoorHallway());
  const auto hit = scene.Raycast({138.0, 0.0}, {0.0, 1.0}, 1000.0, 30.0);
  ASSERT_TRUE(hit.has_value());
  EXPECT_THAT(hit->distance_in, DoubleNear(37.0, 1e-9));
  EXPECT_EQ(hit->surface, SurfaceType::kWood);
}

TEST(SceneTest, RaycastThroughOpenDoorReachesTheRoomBackWall) {
  const Scene scene(DoorHallway(DoorState::kOpenInward, DegToRad(90.0)));
  const auto hit = scene.Raycast({138.0, 0.0}, {0.0, 1.0}, 1000.0, 30.0);
  ASSERT_TRUE(hit.has_value());
  EXPECT_THAT(hit->distance_in, DoubleNear(36.0 + 144.0, 1e-9));
}

TEST(SceneTest, OutwardOpenLeafStandsInTheHallway) {
  // Hinged at x = 120, swung 90° into the hallway: the leaf spans y = 35 .. -1 at x = 120.
  const Scene scene(DoorHallway(DoorState::kOpenOutward, DegToRad(90.0)));
  const auto hit = scene.Raycast({100.0, 10.0}, {1.0, 0.0}, 1000.0, 30.0);
  ASSERT_TRUE(hit.has_value());
  EXPECT_THAT(hit->distance_in, DoubleNear(20.0, 1e-9));
  EXPECT_EQ(hit->surface, SurfaceType::kWood);
}

TEST(SceneTest, RaycastAboveTheDoorHitsTheHeader) {
  const Scene scene(DoorHallway(DoorState::kOpenInward, DegToRad(90.0)));
  const auto hit = scene.Raycast({138.0, 0.0}, {0.0, 1.0}, 1000.0, 88.0);
  ASSERT_TRUE(hit.has_value());
  EXPECT_THAT(hit->distance_in, DoubleNear(36.0, 1e-9));
}

TEST(SceneTest, NearestInConeIsPerpendicularDistanceWhenNormalInsideCone) {
  const Scene scene(DoorHallway());
  const double tilt = DegToRad(10.0);  // inside an 11.8° half cone
  const auto hit = scene.NearestInCone({50.0, 0.0}, {std::sin(tilt), std::cos(tilt)},
                                       DegToRad(11.8), 1000.0, 30.0);
  ASSERT_TRUE(hit.has_value());
  EXPECT_THAT(hit->distance_in, DoubleNear(36.0, 1e-9));
  EXPECT_THAT(hit->incidence_rad, DoubleNear(tilt, 1e-9));
}

TEST(SceneTest, NearestInConeFollowsConeLimitWhenNormalOutsideCone) {
  // §5.4.1 Cases 2 and 3: the return comes along the cone edge nearest the normal.
  const Scene scene(DoorHallway());
  const double tilt = DegToRad(30.0);
  const double half = DegToRad(11.8);
  const auto hit =
      scene.NearestInCone({50.0, 0.0}, {std::sin(tilt), std::cos(tilt)}, half, 1000.0, 30.0);
  ASSERT_TRUE(hit.has_value());
  EXPECT_THAT(hit->distance_in, DoubleNear(36.0 / std::cos(tilt - half), 1e-9));
}

TEST(SceneTest, NearestInConeReturnsNothingBeyondMaxRange) {
  const Scene scene(DoorHallway());
  EXPECT_FALSE(scene.NearestInCone({50.0, 0.0}, {0.0, 1.0}, DegToRad(11.8), 30.0, 30.0));
}

}  // namespace
}  // namespace stickrep::world
