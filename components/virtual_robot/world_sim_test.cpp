#include "virtual_robot/world_sim.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "stickrep/floor_plan.h"

namespace stickrep::virtual_robot {
namespace {

using ::testing::DoubleNear;

// A square closed ring, 400 in a side, with one 36 in door in the middle of the first side.
map::Map SquareRing() {
  map::Ring ring;
  ring.id = "square";
  ring.edges = {map::Edge::Wall(182), map::Edge::Door(map::DoorClass::k36),
                map::Edge::Wall(182), map::Edge::Wall(400),
                map::Edge::Wall(400), map::Edge::Wall(400)};
  const double xs[] = {0, 182, 218, 400, 400, 0};
  const double ys[] = {0, 0, 0, 0, 400, 400};
  // Ring order walks with the wall on the right, so the square is walked clockwise:
  // along +x at y = 0 the hallway (left of travel) lies at y > 0... inside the square.
  ring.nodes.resize(6);
  for (int i = 0; i < 6; ++i) {
    ring.nodes[i].x_in = xs[i];
    ring.nodes[i].y_in = ys[i];
    ring.nodes[i].angle_deg = (i == 0 || i >= 3) ? 90.0 : 180.0;
  }
  return map::Map(map::MapInfo{"square", "", "", std::nullopt}, {ring});
}

WorldSimConfig Exact() {
  WorldSimConfig c;
  c.hallway_width_in = 120.0;
  c.sonar_surface_errors = false;
  c.wheel_slip_stddev = 0.0;
  c.image_noise_sigma = 0.0;
  return c;
}

TEST(WorldSimTest, ForwardTravelMovesAgainstRingOrderByTheWheelTravel) {
  WorldSim sim(SquareRing(), sensing::RobotConfig{}, Exact(), 150.0, 1);
  const SimTruth before = sim.Truth();
  sim.Step(1.0, 2.0, 2.0);  // 24 in
  const SimTruth after = sim.Truth();
  EXPECT_EQ(after.edge_index, before.edge_index);
  EXPECT_THAT(after.offset_in, DoubleNear(before.offset_in - 24.0, 1e-9));
  EXPECT_THAT(after.X_WR.x_in, DoubleNear(before.X_WR.x_in - 24.0, 1e-9));
  EXPECT_FALSE(after.forward_in_ring);
  EXPECT_THAT(sim.left_travel_in(), DoubleNear(24.0, 1e-9));
}

TEST(WorldSimTest, RobotRunsOnTheHallwayAxisFacingAgainstRingOrder) {
  WorldSim sim(SquareRing(), sensing::RobotConfig{}, Exact(), 100.0, 1);
  const SimTruth t = sim.Truth();
  EXPECT_THAT(t.X_WR.y_in, DoubleNear(60.0, 1e-9));
  EXPECT_THAT(std::abs(t.X_WR.theta_rad), DoubleNear(M_PI, 1e-9));
  EXPECT_THAT(t.offset_in, DoubleNear(t.X_WR.x_in, 1e-9));  // abreast of the camera
}

TEST(WorldSimTest, AxisTurnsBeforeTheWallAheadAtACorner) {
  // Node 0 joins the last side (x = 0, walked toward -y) to the first (y = 0): the axis
  // corner lies half the hallway from both walls, not on either.
  WorldSim sim(SquareRing(), sensing::RobotConfig{}, Exact(), 0.0, 1);
  const SimTruth t = sim.Truth();
  EXPECT_THAT(t.X_WR.x_in, DoubleNear(60.0, 1e-9));
  EXPECT_THAT(t.X_WR.y_in, DoubleNear(60.0, 1e-9));
}

TEST(WorldSimTest, CoaxialSonarReadsTheMappedWallAtHalfTheHallway) {
  const sensing::RobotConfig robot;
  WorldSim sim(SquareRing(), robot, Exact(), 100.0, 1);
  const auto r = sim.Sonar();
  EXPECT_THAT(static_cast<double>(r[robot.camera.coaxial_sensor]),
              DoubleNear(60.0 - robot.sonar_ring.head_radius_in, 0.5));
}

TEST(WorldSimTest, FrameHasTheCameraSizeAndShowsTheDoorEdges) {
  WorldSim sim(SquareRing(), sensing::RobotConfig{}, Exact(), 200.0, 1);
  const std::vector<uint8_t> img = sim.RenderFrame();
  ASSERT_EQ(img.size(), static_cast<size_t>(sim.image_width_px() * sim.image_height_px()));
  // Along the centre row the door and its frame make strong intensity steps.
  const int w = sim.image_width_px(), row = sim.image_height_px() / 2;
  int steps = 0;
  for (int u = 1; u < w; ++u) steps += std::abs(img[row * w + u] - img[row * w + u - 1]) > 20;
  EXPECT_GE(steps, 2);
}

TEST(WorldSimTest, TeleportMovesTheRobotButNotTheEncoders) {
  WorldSim sim(SquareRing(), sensing::RobotConfig{}, Exact(), 100.0, 1);
  sim.Step(1.0, 1.0, 1.0);
  const double travel = sim.left_travel_in();
  sim.Teleport(900.0);
  EXPECT_EQ(sim.Truth().edge_index, 4);
  EXPECT_EQ(sim.left_travel_in(), travel);
}

// A corridor outline's axis runs down the corridor and back on the same line, one stretch
// per side. The travel direction must be judged on the side the camera watches, so that it
// agrees with the ring order of the edges the camera sees, driving forward or backward.
TEST(WorldSimTest, CorridorOutlineTravelDirectionFollowsTheWatchedSideBothWays) {
  const map::Map corridor = map::ParseFloorPlan(R"(stickrep_floor: 1
name: straight
corridors:
  - id: c
    width_in: 96
    start: {xy_in: [0, 0], heading_deg: 0}
    path:
      - straight_in: 700
    ends: {start: wall, end: wall}
    right:
      - {at_in: 200, door_in: 36}
    left:
      - {at_in: 400, door_in: 36}
)", "straight.floor.yaml");
  WorldSimConfig c = Exact();
  c.ring_id = "c";
  // Starts on one side of the corridor and on the other.
  for (const double start_in : {150.0, 450.0, 900.0, 1200.0}) {
    WorldSim sim(corridor, sensing::RobotConfig{}, c, start_in, 1);
    for (const double speed : {1.0, -1.0, 1.0}) {
      const SimTruth before = sim.Truth();
      sim.Step(0.5, speed, speed);  // 6 in
      const SimTruth after = sim.Truth();
      ASSERT_EQ(after.edge_index, before.edge_index) << "start " << start_in;
      const bool up_the_ring = after.offset_in > before.offset_in;
      EXPECT_EQ(after.forward_in_ring, up_the_ring) << "start " << start_in << ", speed " << speed;
    }
  }
}

TEST(WorldSimTest, UnknownRingIsRejected) {
  WorldSimConfig c = Exact();
  c.ring_id = "nowhere";
  EXPECT_THROW(WorldSim(SquareRing(), sensing::RobotConfig{}, c, 0.0, 1), std::invalid_argument);
}

}  // namespace
}  // namespace stickrep::virtual_robot
