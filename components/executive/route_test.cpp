#include "executive/route.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "stickrep/map_io.h"
#include "stickrep/test_maps.h"

namespace stickrep::executive {
namespace {

using ::testing::DoubleNear;
using ::testing::HasSubstr;

// The box of test_maps.h: ring "box" (closed, 400 in round: wall 40, door 36, wall 24, then
// three 100 in walls), and the open ring "strip" (wall 50, door 32) whose node 0 at
// (0, 200) is joined to the box's node 0 at (0, 100), 100 in across.
class RouteTest : public ::testing::Test {
 protected:
  map::Map map_ = map::ParseMap(map::testing::kBoxMapYaml, "box.yaml");
  RoutePlanner planner_{map_};
  int box_ = map_.FindRing("box");
  int strip_ = map_.FindRing("strip");
};

TEST_F(RouteTest, GoalAheadKeepsTheTravelDirection) {
  // 10 in into the first wall, travelling in ring order; the door's middle is 40 + 18 in
  // from node 0.
  const RouteResult r = planner_.Plan({box_, 0, +1, 10.0}, "box/1");
  ASSERT_TRUE(r) << r.error;
  EXPECT_THAT(r.route->distance_in, DoubleNear(48.0, 1e-9));
  ASSERT_EQ(r.route->legs.size(), 1u);
  EXPECT_EQ(r.route->legs[0].dir, +1);
  EXPECT_EQ(r.route->initial_travel_sign, +1);
  EXPECT_TRUE(r.route->crossings.empty());
}

TEST_F(RouteTest, GoalBehindIsReachedTheShorterWayRoundTheClosedRing) {
  // At 50 in from node 0 (10 in into the door) heading in ring order; the last wall's
  // middle is 300 in ahead but only 100 in behind.
  const RouteResult r = planner_.Plan({box_, 1, +1, 10.0}, "box/5");
  ASSERT_TRUE(r) << r.error;
  EXPECT_THAT(r.route->distance_in, DoubleNear(100.0, 1e-9));
  ASSERT_EQ(r.route->legs.size(), 1u);
  EXPECT_EQ(r.route->legs[0].dir, -1);
  EXPECT_EQ(r.route->initial_travel_sign, -1);
  // The same goal travelling against ring order is straight ahead.
  const RouteResult ahead = planner_.Plan({box_, 1, -1, 26.0}, "box/5");
  ASSERT_TRUE(ahead) << ahead.error;
  EXPECT_THAT(ahead.route->distance_in, DoubleNear(100.0, 1e-9));
  EXPECT_EQ(ahead.route->initial_travel_sign, +1);
}

TEST_F(RouteTest, GoalBehindInsideTheSameEdgeReverses) {
  const RouteResult r = planner_.Plan({box_, 3, +1, 80.0}, "box/3");
  ASSERT_TRUE(r) << r.error;
  EXPECT_THAT(r.route->distance_in, DoubleNear(30.0, 1e-9));
  EXPECT_EQ(r.route->initial_travel_sign, -1);
}

TEST_F(RouteTest, GoalOnAnotherRingCrossesTheJoin) {
  // Back 50 in to node 0, across 100 in to the strip, 50 + 16 in along it to the door.
  const RouteResult r = planner_.Plan({box_, 1, +1, 10.0}, "strip/1");
  ASSERT_TRUE(r) << r.error;
  const Route& route = *r.route;
  EXPECT_THAT(route.distance_in, DoubleNear(216.0, 1e-9));
  ASSERT_EQ(route.legs.size(), 2u);
  ASSERT_EQ(route.crossings.size(), 1u);
  EXPECT_EQ(route.legs[0].ring, box_);
  EXPECT_EQ(route.legs[0].dir, -1);
  EXPECT_THAT(route.legs[0].distance_in, DoubleNear(50.0, 1e-9));
  EXPECT_EQ(route.legs[0].end_node, 0);
  EXPECT_EQ(route.crossings[0].from_ring, box_);
  EXPECT_EQ(route.crossings[0].from_node, 0);
  EXPECT_EQ(route.crossings[0].to_ring, strip_);
  EXPECT_EQ(route.crossings[0].to_node, 0);
  EXPECT_THAT(route.crossings[0].distance_in, DoubleNear(100.0, 1e-9));
  EXPECT_EQ(route.legs[1].ring, strip_);
  EXPECT_EQ(route.legs[1].dir, +1);
  EXPECT_THAT(route.legs[1].distance_in, DoubleNear(66.0, 1e-9));
  EXPECT_EQ(route.initial_travel_sign, -1);
  EXPECT_THAT(planner_.Describe(route), HasSubstr("cross at node 0 to ring strip node 0"));
}

TEST_F(RouteTest, NodeGoalsAndBackAcrossTheJoin) {
  const RouteResult r = planner_.Plan({box_, 1, +1, 10.0}, "strip/node/2");
  ASSERT_TRUE(r) << r.error;
  EXPECT_THAT(r.route->distance_in, DoubleNear(232.0, 1e-9));
  EXPECT_EQ(r.route->legs.back().end_node, 2);
  // From the strip's door back to the box's door: 66 + 100 + 58 in.
  const RouteResult back = planner_.Plan({strip_, 1, -1, 16.0}, " box/1 ");
  ASSERT_TRUE(back) << back.error;
  EXPECT_THAT(back.route->distance_in, DoubleNear(224.0, 1e-9));
  EXPECT_EQ(back.route->initial_travel_sign, +1);
}

TEST_F(RouteTest, UniquePatternNamesADoor) {
  const GoalResult g = planner_.ParseGoal("pattern:poster");
  ASSERT_TRUE(g) << g.error;
  EXPECT_EQ(g.goal->ring, box_);
  EXPECT_EQ(g.goal->index, 1);
}

TEST_F(RouteTest, BadGoalsReturnTheReason) {
  const auto error = [&](const std::string& name) { return planner_.ParseGoal(name).error; };
  EXPECT_THAT(error("nowhere/1"), HasSubstr("has no ring 'nowhere'"));
  EXPECT_THAT(error("box/99"), HasSubstr("edge 99 is out of range: ring 'box' has 6 edges"));
  EXPECT_THAT(error("strip/node/3"), HasSubstr("node 3 is out of range"));
  EXPECT_THAT(error("box/-1"), HasSubstr("is not an index"));
  EXPECT_THAT(error("box"), HasSubstr("malformed"));
  EXPECT_THAT(error("box/door/1"), HasSubstr("malformed"));
  EXPECT_THAT(error(""), HasSubstr("empty goal name"));
  EXPECT_THAT(error("pattern:old_window"), HasSubstr("no edge of map 'box' has pattern"));
  const RouteResult r = planner_.Plan({box_, 0, +1, 0.0}, "box/7");
  EXPECT_FALSE(r);
  EXPECT_THAT(r.error, HasSubstr("out of range"));
}

TEST_F(RouteTest, PoseOffTheMapIsAnError) {
  EXPECT_THAT(planner_.Plan({7, 0, +1, 0.0}, "box/1").error, HasSubstr("not on the map"));
  EXPECT_THAT(planner_.Plan({box_, 0, 0, 0.0}, "box/1").error, HasSubstr("not on the map"));
}

TEST(RouteStandaloneTest, RingWithoutAJoinIsUnreachable) {
  std::string yaml = map::testing::kBoxMapYaml;
  yaml.erase(yaml.find("joins:"));
  const map::Map m = map::ParseMap(yaml, "nojoin.yaml");
  RoutePlanner planner(m);
  const RouteResult r = planner.Plan({m.FindRing("box"), 0, +1, 0.0}, "strip/1");
  EXPECT_FALSE(r);
  EXPECT_THAT(r.error, HasSubstr("cannot be reached"));
}

TEST(RouteStandaloneTest, ShippedMapPatternsAndJoins) {
  const map::Map m =
      map::LoadMap(std::string(STICKREP_SOURCE_DIR) + "/maps/wells_hall_7f_modified.yaml");
  RoutePlanner planner(m);
  EXPECT_TRUE(planner.ParseGoal("pattern:artificial_ribbon")) << "the reference ribbon";
  const int core = m.FindRing("core");
  ASSERT_GE(core, 0);
  const RouteResult r = planner.Plan({core, 3, +1, 0.0}, "corridor_outer/10");
  ASSERT_TRUE(r) << r.error;
  EXPECT_EQ(r.route->crossings.size(), 1u);
  const map::Map eb =
      map::LoadMap(std::string(STICKREP_SOURCE_DIR) + "/maps/engineering_building_3f.yaml");
  EXPECT_THAT(RoutePlanner(eb).ParseGoal("pattern:poster").error, HasSubstr("name the edge"));
}

}  // namespace
}  // namespace stickrep::executive
