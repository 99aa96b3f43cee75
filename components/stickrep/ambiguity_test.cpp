#include "stickrep/ambiguity.h"

#include <gtest/gtest.h>

#include "stickrep/map_io.h"
#include "stickrep/test_maps.h"

namespace stickrep::map {
namespace {

// The box ring alone (the strip's open end would stop starts there).
Map BoxOnly() {
  const Map both = ParseMap(testing::kBoxMapYaml, "box.yaml");
  return Map(both.info(), {both.ring(0)});
}

const StartResult& Start(const AmbiguityResult& r, int edge, int dir) {
  for (const StartResult& s : r.starts) {
    if (s.start.edge == edge && s.start.dir == dir) return s;
  }
  throw std::out_of_range("no such start");
}

TEST(AmbiguityTest, WholeFirstEdgeGivesTheHandCountedAnswer) {
  AmbiguityOptions o;
  o.partial_first_edge = false;
  const AmbiguityResult r = AnalyseAmbiguity(BoxOnly(), o);
  ASSERT_EQ(r.starts.size(), 12u);
  EXPECT_EQ(r.unique, 12);
  // Worked by hand: the first edge leaves both directions open, so every start needs 2
  // edges, except four starts on the three 100 in walls: 4, 3, 3, 4.
  EXPECT_EQ(Start(r, 3, +1).edges, 4);
  EXPECT_EQ(Start(r, 5, -1).edges, 4);
  EXPECT_EQ(Start(r, 4, +1).edges, 3);
  EXPECT_EQ(Start(r, 4, -1).edges, 3);
  EXPECT_EQ(Start(r, 1, +1).edges, 2);
  EXPECT_DOUBLE_EQ(r.mean_edges, 30.0 / 12.0);
  EXPECT_EQ(r.max_edges, 4);
}

TEST(AmbiguityTest, PartialFirstWallNeedsMoreContext) {
  const AmbiguityResult r = AnalyseAmbiguity(BoxOnly());
  // Inside the 40 in wall towards the door: "some wall, door 36" also fits the 24 in wall
  // travelled backwards, so the next wall (24 in) is needed.
  EXPECT_EQ(Start(r, 0, +1).edges, 3);
  // Inside a 100 in wall going clockwise, the 40 in wall is needed, as with a whole edge.
  EXPECT_EQ(Start(r, 3, +1).edges, 4);
  EXPECT_GE(r.mean_edges, 30.0 / 12.0);
}

TEST(AmbiguityTest, SymmetricRingIsNeverUnique) {
  Ring ring;
  ring.id = "square";
  double xy[4][2] = {{0, 100}, {100, 100}, {100, 0}, {0, 0}};
  for (int i = 0; i < 4; ++i) {
    ring.edges.push_back(Edge::Wall(100));
    Node n;
    n.angle_deg = 90;
    n.x_in = xy[i][0];
    n.y_in = xy[i][1];
    ring.nodes.push_back(n);
  }
  const AmbiguityResult r = AnalyseAmbiguity(Map({}, {ring}));
  EXPECT_EQ(r.never_unique, 8);
  EXPECT_EQ(r.unique, 0);
}

TEST(AmbiguityTest, OpenRingEndIsReported) {
  const Map both = ParseMap(testing::kBoxMapYaml, "box.yaml");
  const AmbiguityResult r = AnalyseAmbiguity(Map(both.info(), {both.ring(1)}));
  // From the door backwards: door, then the 50 in wall: unique. From the door forwards the
  // ring ends after one edge with two candidates.
  EXPECT_EQ(r.ring_end, 2);
}

}  // namespace
}  // namespace stickrep::map
