#include "stickrep/census.h"

#include <gtest/gtest.h>

#include "stickrep/map_io.h"
#include "stickrep/test_maps.h"

namespace stickrep::map {
namespace {

TEST(CensusTest, CountsPairsByAngleInRingOrder) {
  const Census c = ComputeCensus(ParseMap(testing::kBoxMapYaml, "box.yaml"));
  // Box: four wall-wall corners at 90, wall->door36 and door36->wall at 180.
  EXPECT_EQ(c.pairs[0][kCensusWall][kCensusWall], 4);
  EXPECT_EQ(c.pairs[1][kCensusWall][kCensusDoor36], 1);
  EXPECT_EQ(c.pairs[1][kCensusDoor36][kCensusWall], 1);
  // Strip: wall->door32 at 180; its first node is artificial but an open ring's ends pair
  // nothing anyway.
  EXPECT_EQ(c.pairs[1][kCensusWall][kCensusDoor32], 1);
  EXPECT_EQ(c.pairs_counted, 7);  // six round the closed box, one in the strip
  EXPECT_EQ(c.pairs_artificial, 0);
}

TEST(CensusTest, CountsTriplesAndDoorMarks) {
  const Census c = ComputeCensus(ParseMap(testing::kBoxMapYaml, "box.yaml"));
  EXPECT_EQ(c.wall_door_wall[kCensusDoor36], 1);
  EXPECT_EQ(c.door_census[kCensusDoor36][0], 1);  // all doors of the class
  EXPECT_EQ(c.door_census[kCensusDoor36][5], 1);  // poster
  EXPECT_EQ(c.door_census[kCensusDoor32][0], 1);
}

TEST(CensusTest, WallCensusUsesTheThresholdsOfTable69) {
  const Census c = ComputeCensus(ParseMap(testing::kBoxMapYaml, "box.yaml"));
  // Walls: 40, 24, 100, 100, 100, 50.
  EXPECT_EQ(c.walls, 6);
  EXPECT_EQ(c.wall_census[0], 6);  // > 0
  EXPECT_EQ(c.wall_census[3], 5);  // >= 32
  EXPECT_EQ(c.wall_census[4], 4);  // >= 48
  EXPECT_EQ(c.wall_census[7], 3);  // >= 96
  EXPECT_EQ(c.wall_census[8], 0);  // >= 112
}

TEST(CensusTest, DoubleDoorCountsAsTwoLeavesWithACoplanarPair) {
  Ring ring;
  ring.id = "r";
  ring.closed = false;
  ring.edges = {Edge::Wall(10), Edge::Door(DoorClass::k30_30), Edge::Wall(10)};
  ring.nodes.resize(4);
  const Census c = ComputeCensus(Map({}, {ring}));
  EXPECT_EQ(c.leaf_edges, 4);
  EXPECT_EQ(c.door_leaves, 2);
  EXPECT_EQ(c.pairs[1][kCensusDoor30][kCensusDoor30], 1);
  EXPECT_EQ(c.pairs[1][kCensusWall][kCensusDoor30], 1);
  EXPECT_EQ(c.pairs[1][kCensusDoor30][kCensusWall], 1);
  EXPECT_EQ(c.door_census[kCensusDoor30][0], 2);
}

TEST(CensusTest, PairsAcrossArtificialNodesAreNotCounted) {
  Ring ring;
  ring.id = "r";
  ring.closed = true;
  ring.edges = {Edge::Wall(10), Edge::Wall(10)};
  ring.nodes.resize(2);
  ring.nodes[0].angle_deg = 90;
  ring.nodes[1].angle_deg = 90;
  ring.nodes[1].artificial = true;
  const Census c = ComputeCensus(Map({}, {ring}));
  EXPECT_EQ(c.pairs_counted, 1);
  EXPECT_EQ(c.pairs_artificial, 1);
}

}  // namespace
}  // namespace stickrep::map
