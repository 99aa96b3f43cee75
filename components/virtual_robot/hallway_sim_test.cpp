#include "virtual_robot/hallway_sim.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace stickrep::virtual_robot {
namespace {

using ::testing::DoubleNear;

// wall 100 in, door 36, wall 64: a closed ring 200 in long.
map::Map SmallMap() {
  map::Ring ring;
  ring.id = "hall";
  ring.edges = {map::Edge::Wall(100.0), map::Edge::Door(map::DoorClass::k36),
                map::Edge::Wall(64.0)};
  ring.nodes.resize(3);
  return map::Map(map::MapInfo{"small", "", "", std::nullopt}, {ring});
}

TEST(HallwaySimTest, EqualWheelSpeedsMoveAlongTheHallwayAndWrapAroundTheRing) {
  HallwaySim sim(SmallMap(), SimWorldConfig{}, SimRobotConfig{}, 190.0, 1);
  sim.Step(1.0, 1.0, 1.0);  // 12 in forward
  EXPECT_THAT(sim.Truth().x_in, DoubleNear(2.0, 1e-9));
  EXPECT_EQ(sim.Truth().edge_index, 0);
  EXPECT_THAT(sim.left_travel_in(), DoubleNear(12.0, 1e-9));
}

TEST(HallwaySimTest, WheelSpeedsAreClampedToTheTopSpeed) {
  HallwaySim sim(SmallMap(), SimWorldConfig{}, SimRobotConfig{}, 0.0, 1);
  sim.Step(1.0, 10.0, 10.0);
  EXPECT_THAT(sim.Truth().distance_in, DoubleNear(2.6 * 12.0, 1e-9));
}

TEST(HallwaySimTest, CoaxialSonarReadsTheWallSquareOn) {
  SimWorldConfig world;
  world.hallway_width_in = 96.0;
  SimRobotConfig robot;
  HallwaySim sim(SmallMap(), world, robot, 50.0, 1);
  const SonarRanges r = sim.Sonar();
  EXPECT_THAT(static_cast<double>(r[0]), DoubleNear(48.0 - robot.head_radius_in, 1e-4));
  EXPECT_THAT(static_cast<double>(r[12]), DoubleNear(48.0 - robot.head_radius_in, 1e-4));  // the opposite wall
  EXPECT_EQ(r[6], 0.0f);  // straight along the hallway: no wall, no echo
}

TEST(HallwaySimTest, DoorJambsAppearAsDarkColumnsWhereThePinholeModelPutsThem) {
  SimWorldConfig world;
  world.image_noise_sigma = 0.0;
  SimRobotConfig robot;
  // The door spans x = 100..136; put the optical axis on its centre.
  HallwaySim sim(SmallMap(), world, robot, 118.0, 1);
  const std::vector<uint8_t> img = sim.RenderFrame();
  const int w = robot.image_width_px, row = robot.image_height_px / 2;
  const double f = 0.5 * w / std::tan(robot.fov_deg * M_PI / 360.0);
  const double d = 48.0;
  // The jambs frame the 36 in opening from outside: x = 98..100 and 136..138.
  const int left_jamb = static_cast<int>(0.5 * w + (100.0 - 1.0 - 118.0) * f / d);
  const int right_jamb = static_cast<int>(0.5 * w + (136.0 + 1.0 - 118.0) * f / d);
  EXPECT_EQ(img[row * w + left_jamb], 50);
  EXPECT_EQ(img[row * w + right_jamb], 50);
  EXPECT_EQ(img[row * w + w / 2], 110);  // door face
  EXPECT_EQ(img[row * w + 5], 170);      // wall
}

}  // namespace
}  // namespace stickrep::virtual_robot
