#include "stickrep/map.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "stickrep/map_io.h"
#include "stickrep/test_maps.h"

namespace stickrep::map {
namespace {

Map Box() { return ParseMap(testing::kBoxMapYaml, "box.yaml"); }

TEST(DoorMarkTest, APatternNamesAMarkOnlyWhereItSaysOne) {
  EXPECT_EQ(DoorMarkOfPattern("poster"), DoorMark::kPoster);
  EXPECT_EQ(DoorMarkOfPattern("two_new_windows"), DoorMark::kWindow);
  EXPECT_EQ(DoorMarkOfPattern("old_window"), DoorMark::kWindow);
  EXPECT_EQ(DoorMarkOfPattern("no_window"), DoorMark::kPlain);
  EXPECT_EQ(DoorMarkOfPattern("plain"), DoorMark::kPlain);
  // Not surveyed, or a mark the camera cannot tell: no claim about the leaf.
  EXPECT_EQ(DoorMarkOfPattern(""), DoorMark::kUnknown);
  EXPECT_EQ(DoorMarkOfPattern("kick_plate"), DoorMark::kUnknown);
  for (const DoorMark m : {DoorMark::kUnknown, DoorMark::kPlain, DoorMark::kWindow,
                           DoorMark::kPoster}) {
    EXPECT_EQ(ParseDoorMark(DoorMarkName(m)), m);
  }
  EXPECT_FALSE(ParseDoorMark("glass"));
}

TEST(MapTraversalTest, ForwardWrapsAroundAClosedRing) {
  const Map map = Box();
  Cursor c{0, 5, +1};
  ASSERT_TRUE(map.Advance(c));
  EXPECT_EQ(c.edge, 0);
  EXPECT_DOUBLE_EQ(map.EdgeAt(0, 6).metric_in, 40.0);
}

TEST(MapTraversalTest, BackwardWrapsAroundAClosedRing) {
  const Map map = Box();
  Cursor c{0, 0, -1};
  ASSERT_TRUE(map.Advance(c));
  EXPECT_EQ(c.edge, 5);
  EXPECT_EQ(map.Wrap(0, -1), 5);
  EXPECT_EQ(map.Wrap(0, -13), 5);
}

TEST(MapTraversalTest, OpenRingStopsAtBothEnds) {
  const Map map = Box();
  Cursor fwd{1, 1, +1};
  EXPECT_FALSE(map.Advance(fwd));
  EXPECT_EQ(fwd.edge, 1);
  Cursor back{1, 0, -1};
  EXPECT_FALSE(map.Advance(back));
  EXPECT_EQ(map.Wrap(1, 2), -1);
}

TEST(MapTraversalTest, NodeAheadDependsOnTheDirection) {
  const Map map = Box();
  // Edge 2 (wall 24) runs from node 2 (180) to node 3 (90).
  EXPECT_DOUBLE_EQ(map.NodeAhead({0, 2, +1}).angle_deg, 90.0);
  EXPECT_DOUBLE_EQ(map.NodeAhead({0, 2, -1}).angle_deg, 180.0);
  EXPECT_DOUBLE_EQ(map.NodeBehind({0, 2, +1}).angle_deg, 180.0);
  // The last edge of a closed ring ends at node 0.
  EXPECT_DOUBLE_EQ(map.NodeAhead({0, 5, +1}).x_in, 0.0);
  EXPECT_DOUBLE_EQ(map.NodeAhead({0, 5, +1}).y_in, 100.0);
  // The last edge of an open ring ends at its extra node.
  EXPECT_DOUBLE_EQ(map.NodeAhead({1, 1, +1}).x_in, 82.0);
}

TEST(MapTraversalTest, AFullLapVisitsEveryEdgeOnce) {
  const Map map = Box();
  Cursor c{0, 3, -1};
  double sum = 0;
  for (int i = 0; i < 6; ++i) {
    sum += map.EdgeAt(c.ring, c.edge).metric_in;
    ASSERT_TRUE(map.Advance(c));
  }
  EXPECT_DOUBLE_EQ(sum, 400.0);
  EXPECT_EQ(c.edge, 3);
}

TEST(MapModelTest, FindsRingsById) {
  const Map map = Box();
  EXPECT_EQ(map.FindRing("strip"), 1);
  EXPECT_EQ(map.FindRing("nope"), -1);
}

TEST(MapModelTest, ConstructorRejectsAWrongNodeCount) {
  Ring ring;
  ring.id = "r";
  ring.closed = false;
  ring.edges = {Edge::Wall(10)};
  ring.nodes = {Node{}};
  EXPECT_THROW(Map({}, {ring}), std::invalid_argument);
}

TEST(DoorRowTest, DoorsBesideOrAcrossAShortWallAreARowAndTheShortWallWithThem) {
  Ring ring;
  ring.closed = false;
  // 0 wall, 1 door, 2 short wall, 3 door, 4 door, 5 long wall, 6 door, 7 wall just at the
  // limit, 8 door, 9 wall.
  ring.edges = {Edge::Wall(200),
                Edge::Door(DoorClass::k36),
                Edge::Wall(46),
                Edge::Door(DoorClass::k36_36),
                Edge::Door(DoorClass::k40),
                Edge::Wall(300),
                Edge::Door(DoorClass::k32),
                Edge::Wall(kRowWallIn),
                Edge::Door(DoorClass::k30),
                Edge::Wall(100)};
  const std::vector<bool> row = {false, true, true, true, true, false, false, false, false, false};
  for (int k = 0; k < ring.EdgeCount(); ++k) EXPECT_EQ(InDoorRow(ring, k), row[k]) << "edge " << k;
  // Open ring: the first door has nothing before it; closed, the last wall joins it to the
  // first door round the ring when short.
  ring.edges[0] = Edge::Door(DoorClass::k36);
  ring.edges[9] = Edge::Wall(20);
  EXPECT_TRUE(InDoorRow(ring, 0));  // beside door 1
  EXPECT_FALSE(InDoorRow(ring, 9));
  EXPECT_FALSE(InDoorRow(ring, 8));
  ring.closed = true;
  EXPECT_TRUE(InDoorRow(ring, 9));
  EXPECT_TRUE(InDoorRow(ring, 8));
}

TEST(MapModelTest, DoorClassesRoundTripByName) {
  for (int k = 0; k < kDoorClassCount; ++k) {
    const auto cls = static_cast<DoorClass>(k);
    EXPECT_EQ(ParseDoorClass(DoorClassName(cls)), cls);
  }
  EXPECT_DOUBLE_EQ(DoorClassWidthIn(DoorClass::k36_36), 72.0);
  EXPECT_EQ(LeafClass(DoorClass::k30_30), DoorClass::k30);
  EXPECT_FALSE(ParseDoorClass("34").has_value());
}

}  // namespace
}  // namespace stickrep::map
