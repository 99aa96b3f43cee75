#include "virtual_robot/world_sim.h"

#include "virtual_robot/virtual_robot_config.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/units.h"
#include "map_tool/floor_plan.h"
#include "virtual_robot/test_world.h"

namespace stickrep::virtual_robot {
namespace {

using ::testing::DoubleNear;

using testing::Exact;
using testing::SquareRing;

// The ring position of the place at x on a wall of the ring along y = wall_y (-1: none).
double RingPositionAbreast(const map::Ring& ring, double x_in, double wall_y_in) {
  double s = 0.0;
  for (int e = 0; e < ring.EdgeCount(); ++e) {
    const map::Node& a = ring.nodes[e];
    const map::Node& b = ring.nodes[(e + 1) % ring.NodeCount()];
    if (std::abs(a.y_in - wall_y_in) < 1e-6 && std::abs(b.y_in - wall_y_in) < 1e-6 &&
        std::min(a.x_in, b.x_in) < x_in && std::max(a.x_in, b.x_in) > x_in) {
      return s + std::abs(x_in - a.x_in);
    }
    s += ring.edges[e].metric_in;
  }
  return -1.0;
}

// Turns the base in place (0.2 ft/s on each wheel, opposite ways) until it faces within
// `tolerance_rad` of `theta_rad`.
void TurnInPlaceTo(WorldSim& sim, double theta_rad, double tolerance_rad) {
  for (int i = 0; i < 4000; ++i) {
    const double error = std::remainder(theta_rad - sim.pose().theta_rad, 2.0 * M_PI);
    if (std::abs(error) < tolerance_rad) break;
    const double v = std::copysign(0.2, error);
    sim.Step(0.02, -v, v);
  }
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

TEST(WorldSimTest, RealismChangesTheFramesAndTheSeedReproducesThem) {
  WorldSimConfig real = Exact();
  real.realism = world::FullRealism();
  WorldSim clean(SquareRing(), sensing::RobotConfig{}, Exact(), 200.0, 7);
  WorldSim a(SquareRing(), sensing::RobotConfig{}, real, 200.0, 7);
  WorldSim b(SquareRing(), sensing::RobotConfig{}, real, 200.0, 7);
  const std::vector<std::uint8_t> fc = clean.RenderFrame();
  const std::vector<std::uint8_t> fa = a.RenderFrame();
  EXPECT_EQ(fa, b.RenderFrame());
  EXPECT_NE(fa, fc);
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

// An 88 in corridor, 1200 in long, with an alcove 96 in wide and 48 in deep on its right
// side at 300 in and a hall 480 in wide and 360 in deep on its left at 600 in.
map::Map AlcoveAndHallCorridor() {
  return map::ParseFloorPlan(R"(stickrep_floor: 1
name: alcove_and_hall
corridors:
  - id: c
    width_in: 88
    start: {xy_in: [0, 0], heading_deg: 0}
    path:
      - straight_in: 1200
    ends: {start: wall, end: wall}
    right:
      - {at_in: 300, alcove: {width_in: 96, depth_in: 48}}
    left:
      - {at_in: 600, alcove: {width_in: 480, depth_in: 360}}
)", "alcove_and_hall.floor.yaml");
}

// Ring positions whose edge is the back of the alcove (a wall 96 in long whose two
// neighbours are 48 in walls at right angles).
std::vector<double> AlcoveBackPositions(const map::Ring& ring) {
  std::vector<double> out;
  double s = 0.0;
  const int n = ring.EdgeCount();
  for (int e = 0; e < n; ++e) {
    const double len = ring.edges[e].metric_in;
    if (std::abs(len - 96.0) < 1e-6 && std::abs(ring.edges[(e + n - 1) % n].metric_in - 48.0) < 1e-6 &&
        std::abs(ring.edges[(e + 1) % n].metric_in - 48.0) < 1e-6) {
      for (const double f : {0.1, 0.5, 0.9}) out.push_back(s + f * len);
    }
    s += len;
  }
  return out;
}

TEST(WorldSimTest, AStartAbreastOfAnAlcoveFacesAlongTheCorridor) {
  // The axis offset from the alcove's back is a stub a few inches long between the offsets
  // of its sides: a start placed on it would face across the corridor.
  const map::Map corridor = AlcoveAndHallCorridor();
  WorldSimConfig c = Exact();
  c.ring_id = "c";
  const std::vector<double> starts = AlcoveBackPositions(corridor.ring(0));
  ASSERT_EQ(starts.size(), 3u);
  for (const double start_in : starts) {
    WorldSim sim(corridor, sensing::RobotConfig{}, c, start_in, 1);
    const double heading = sim.Truth().X_WR.theta_rad;
    EXPECT_LT(std::abs(std::sin(heading)), 1e-6) << "start " << start_in << ": heading " << heading;
    EXPECT_LE(std::abs(sim.Truth().X_WR.y_in), 44.0 + 1e-6) << "start " << start_in;
  }
}

TEST(WorldSimTest, TheCameraLookingAcrossAHallIsNotOnTheHallsFarWall) {
  // On the corridor's axis in front of the hall, the camera looks 404 in across it to the
  // far wall: farther than twice the corridor's width, so the truth is the nearest wall.
  const map::Map corridor = AlcoveAndHallCorridor();
  WorldSimConfig c = Exact();
  c.ring_id = "c";
  // Starts abreast of the middle of the walls before the alcove and before the hall: one
  // on each side.
  std::vector<double> starts;
  double s = 0.0;
  for (const map::Edge& e : corridor.ring(0).edges) {
    if (std::abs(e.metric_in - 300.0) < 1e-6 || std::abs(e.metric_in - 600.0) < 1e-6) {
      starts.push_back(s + 0.5 * e.metric_in);
    }
    s += e.metric_in;
  }
  ASSERT_EQ(starts.size(), 2u);
  for (const double start_in : starts) {
    WorldSim sim(corridor, sensing::RobotConfig{}, c, start_in, 1);
    // Along the axis to abreast of the hall's middle (x = 840) at 1 ft/s, forward or back.
    const world::Pose2d p0 = sim.Truth().X_WR;
    ASSERT_GT(std::abs(std::cos(p0.theta_rad)), 0.99);
    const double travel = (840.0 - p0.x_in) / std::cos(p0.theta_rad);
    const double ftps = std::copysign(1.0, travel);
    const int steps = static_cast<int>(std::abs(travel) / 1.2);
    for (int i = 0; i < steps; ++i) sim.Step(0.1, ftps, ftps);
    sim.Step((std::abs(travel) - 1.2 * steps) / 12.0, ftps, ftps);
    const SimTruth t = sim.Truth();
    ASSERT_NEAR(t.X_WR.x_in, 840.0, 1e-6);
    // Whichever side it watches, the edge it is judged on lies within 2 widths of the base.
    const map::Ring& ring = corridor.ring(0);
    const map::Node& a = ring.nodes[t.edge_index];
    const map::Node& b = ring.nodes[(t.edge_index + 1) % ring.NodeCount()];
    const double ax = a.x_in - t.X_WR.x_in, ay = a.y_in - t.X_WR.y_in;
    const double bx = b.x_in - t.X_WR.x_in, by = b.y_in - t.X_WR.y_in;
    const double len2 = (bx - ax) * (bx - ax) + (by - ay) * (by - ay);
    const double f = std::clamp(-(ax * (bx - ax) + ay * (by - ay)) / len2, 0.0, 1.0);
    const double d = std::hypot(ax + f * (bx - ax), ay + f * (by - ay));
    EXPECT_LE(d, 2.0 * 88.0) << "start " << start_in << ": edge " << t.edge_index;
  }
}

TEST(WorldSimTest, APoseIsJudgedOnTheCorridorTheBaseHasGoneOnInto) {
  // A 96 in main corridor with a wing leaving its right side through an 88 in mouth at
  // x = 700..788. A robot started on the main corridor that drives into the wing is judged
  // on the wing's wall it looks at; its start-ring edge stays the main corridor's.
  const map::Map floor = map::ParseFloorPlan(R"(stickrep_floor: 1
name: wing_off_main
corridors:
  - id: main
    width_in: 96
    start: {xy_in: [0, 0], heading_deg: 0}
    path:
      - straight_in: 1200
    ends: {start: wall, end: wall}
    right:
      - {at_in: 700, opening_in: 88}
  - id: wing
    width_in: 88
    start: {xy_in: [744, -48], heading_deg: -90}
    path:
      - straight_in: 500
    ends: {start: opening, end: wall}
)", "wing_off_main.floor.yaml");
  WorldSimConfig c = Exact();
  c.ring_id = "main";
  // A start abreast of the mouth, across from it: the place at x = 744 on the wall at
  // y = 48 (the main corridor's axis is y = 0).
  const double start_in = RingPositionAbreast(floor.ring(floor.FindRing("main")), 744.0, 48.0);
  ASSERT_GE(start_in, 0.0);
  WorldSim sim(floor, sensing::RobotConfig{}, c, start_in, 1);
  EXPECT_EQ(sim.Truth().seen_ring_id, "main");
  EXPECT_EQ(sim.Truth().seen_edge_index, sim.Truth().edge_index);
  EXPECT_DOUBLE_EQ(sim.Truth().seen_offset_in, sim.Truth().offset_in);
  EXPECT_TRUE(sim.Truth().in_ring_hallway);
  // Turn in place to face -y (down the wing), then drive 200 in.
  TurnInPlaceTo(sim, -M_PI / 2.0, DegToRad(0.5));
  ASSERT_NEAR(sim.pose().theta_rad, -M_PI / 2.0, DegToRad(0.5));
  for (int i = 0; i < 170; ++i) sim.Step(0.1, 1.0, 1.0);
  const SimTruth t = sim.Truth();
  ASSERT_LT(t.X_WR.y_in, -150.0);
  EXPECT_EQ(t.seen_ring_id, "wing");
  // Out of the main corridor's hallway: its axis is 150 in and more away, and the envelope
  // is not judged on it.
  EXPECT_FALSE(t.in_ring_hallway);
  EXPECT_GT(std::abs(t.lateral_offset_in), 96.0);
  ASSERT_GE(t.seen_edge_index, 0);
  ASSERT_LT(t.seen_edge_index, t.seen_ring_edge_count);
  const map::Ring& wing = floor.ring(floor.FindRing("wing"));
  EXPECT_EQ(t.seen_ring_edge_count, wing.EdgeCount());
  // The camera looks left of travel, at the wing's wall at x = 788.
  const map::Node& a = wing.nodes[t.seen_edge_index];
  const map::Node& b = wing.nodes[(t.seen_edge_index + 1) % wing.NodeCount()];
  EXPECT_NEAR(a.x_in, 788.0, 1e-6);
  EXPECT_NEAR(b.x_in, 788.0, 1e-6);
  // The camera, square to that wall, meets it abreast of the base.
  EXPECT_NEAR(t.seen_offset_in, std::abs(t.X_WR.y_in - a.y_in), 1.0);
  // Travelling -y along that wall: forward in the wing's ring order when its edge runs -y.
  EXPECT_EQ(t.seen_forward_in_ring, b.y_in < a.y_in);
  // Judged there, a pose on the main corridor is wrong and one on the wing right.
  EXPECT_FALSE(PoseMatchesTruth("main", t.edge_index, t.forward_in_ring, t));
  EXPECT_TRUE(PoseMatchesTruth("wing", t.seen_edge_index, t.seen_forward_in_ring, t));
}

TEST(WorldSimTest, OnACorridorOutlineEitherDirectionAlongTheCorridorIsOnTheAxis) {
  // The camera may watch either wall of a corridor outline: a base turned round to travel the
  // other way keeps to the axis, and its heading error is its angle from the corridor's
  // direction it faces along, not 180°, also abreast of a lobby's mouth, where the wall it now
  // watches is open and the nearest stretch of the axis is the other wall's.
  const map::Map floor = map::ParseFloorPlan(R"(stickrep_floor: 1
name: lobby_mouth
corridors:
  - id: main
    width_in: 96
    start: {xy_in: [0, 0], heading_deg: 0}
    path:
      - straight_in: 1200
    ends: {start: wall, end: wall}
    left:
      - {at_in: 400, alcove: {width_in: 400, depth_in: 300}}
)",
                                             "lobby_mouth.floor.yaml");
  WorldSimConfig c = Exact();
  c.ring_id = "main";
  // Abreast of the mouth's middle on the closed wall (y = -48), facing west along it.
  const double start_in = RingPositionAbreast(floor.ring(floor.FindRing("main")), 600.0, -48.0);
  ASSERT_GE(start_in, 0.0);
  WorldSim sim(floor, sensing::RobotConfig{}, c, start_in, 1);
  ASSERT_NEAR(sim.pose().x_in, 600.0, 1.0);
  const double start_theta = sim.pose().theta_rad;
  EXPECT_NEAR(sim.Truth().heading_error_rad, 0.0, DegToRad(0.5));
  // Turn in place by 170°: 10° short of the other direction along the corridor.
  const double target = std::remainder(start_theta + DegToRad(170.0), 2.0 * M_PI);
  TurnInPlaceTo(sim, target, DegToRad(0.2));
  const SimTruth t = sim.Truth();
  EXPECT_TRUE(t.in_ring_hallway);
  EXPECT_NEAR(std::abs(RadToDeg(t.heading_error_rad)), 10.0, 0.5);
}

TEST(WorldSimTest, UnknownRingIsRejected) {
  WorldSimConfig c = Exact();
  c.ring_id = "nowhere";
  EXPECT_THROW(WorldSim(SquareRing(), sensing::RobotConfig{}, c, 0.0, 1), std::invalid_argument);
}

}  // namespace
}  // namespace stickrep::virtual_robot
