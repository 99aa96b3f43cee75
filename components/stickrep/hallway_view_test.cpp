#include "stickrep/hallway_view.h"

#include <gtest/gtest.h>

#include "stickrep/map_io.h"
#include "stickrep/test_maps.h"

namespace stickrep::map {
namespace {

// One side of a hallway with pilasters: wall 100, a 13 in step in, wall 46, a 13 in step
// out, wall 80, door 36, a 13 in step in, wall 50, then a real corner, a 60 in wall
// across (too deep for a step), and the wall back.
const char* kPilasters = R"(stickrep_map: 1
name: pilasters
description: "test map"
rings:
  - id: side
    closed: false
    path:
      - node: {angle_deg: 180, xyz_in: [0, 0, 0]}
      - edge: {type: hallway, metric_in: 100}
      - node: {angle_deg: 270, xyz_in: [100, 0, 0]}
      - edge: {type: hallway, metric_in: 13}
      - node: {angle_deg: 90, xyz_in: [100, -13, 0]}
      - edge: {type: hallway, metric_in: 46}
      - node: {angle_deg: 90, xyz_in: [146, -13, 0]}
      - edge: {type: hallway, metric_in: 13}
      - node: {angle_deg: 270, xyz_in: [146, 0, 0]}
      - edge: {type: hallway, metric_in: 80}
      - node: {angle_deg: 180, xyz_in: [226, 0, 0]}
      - edge: {type: doorway, class: "36"}
      - node: {angle_deg: 270, xyz_in: [262, 0, 0]}
      - edge: {type: hallway, metric_in: 13}
      - node: {angle_deg: 90, xyz_in: [262, -13, 0]}
      - edge: {type: hallway, metric_in: 50}
      - node: {angle_deg: 90, xyz_in: [312, -13, 0]}
      - edge: {type: hallway, metric_in: 60}
      - node: {angle_deg: 90, xyz_in: [312, -73, 0]}
      - edge: {type: hallway, metric_in: 312}
      - node: {angle_deg: 180, xyz_in: [0, -73, 0]}
)";

TEST(HallwayViewTest, StepsAcrossTheHallwayMergeTheWallsEitherSide) {
  const Map map = ParseMap(kPilasters, "pilasters.yaml");
  const HallwayView view(map);
  EXPECT_EQ(view.steps_removed(), 3);
  const Ring& r = view.view().ring(0);
  // wall 100+46+80 | door 36 | wall 50 | wall 60 | wall 312
  ASSERT_EQ(r.EdgeCount(), 5);
  EXPECT_DOUBLE_EQ(r.edges[0].metric_in, 226.0);
  EXPECT_TRUE(r.edges[1].IsDoor());
  EXPECT_DOUBLE_EQ(r.edges[2].metric_in, 50.0);
  EXPECT_DOUBLE_EQ(r.edges[3].metric_in, 60.0);
  EXPECT_DOUBLE_EQ(r.edges[4].metric_in, 312.0);
  // The door now meets the wall after it coplanar: the step's corners are gone.
  EXPECT_DOUBLE_EQ(r.nodes[2].angle_deg, 180.0);
  EXPECT_DOUBLE_EQ(r.nodes[3].angle_deg, 90.0);  // the 60 in wall is a real corner
  EXPECT_EQ(view.OriginalEdges(0, 0), (std::vector<int>{0, 1, 2, 3, 4}));
  EXPECT_EQ(view.OriginalEdges(0, 1), (std::vector<int>{5, 6}));
  EXPECT_EQ(view.ViewEdge(0, 3), 0);
  EXPECT_EQ(view.ViewEdge(0, 7), 2);
  EXPECT_EQ(view.ViewEdge(0, 9), 4);
}

TEST(HallwayViewTest, PlacesMapBackToTheOriginalEdges) {
  const HallwayView view(ParseMap(kPilasters, "pilasters.yaml"));
  // 120 in into the merged wall in ring order: 20 in into the 46 in wall.
  HallwayView::Place p = view.ToOriginal(0, 0, +1, 120.0);
  EXPECT_EQ(p.edge, 2);
  EXPECT_DOUBLE_EQ(p.offset_in, 20.0);
  // Against ring order the offset runs from the far end: 60 in is 60 in into the 80 in wall.
  p = view.ToOriginal(0, 0, -1, 60.0);
  EXPECT_EQ(p.edge, 4);
  EXPECT_DOUBLE_EQ(p.offset_in, 60.0);
  p = view.ToOriginal(0, 0, -1, 200.0);  // past 80 and 46: 74 into the 100 in wall
  EXPECT_EQ(p.edge, 0);
  EXPECT_DOUBLE_EQ(p.offset_in, 74.0);
  p = view.ToOriginal(0, 1, +1, 10.0);
  EXPECT_EQ(p.edge, 5);
  p = view.ToOriginal(0, 0, +1, 500.0);  // beyond the end: the last wall, clamped
  EXPECT_EQ(p.edge, 4);
  EXPECT_DOUBLE_EQ(p.offset_in, 80.0);
}

TEST(HallwayViewTest, ZeroStepKeepsEveryEdgeAndJoinsSurvive) {
  const Map map = ParseMap(kPilasters, "pilasters.yaml");
  const HallwayView none(map, HallwayViewConfig{0.0, 30.0, {}});
  EXPECT_EQ(none.steps_removed(), 0);
  EXPECT_EQ(none.view().ring(0).EdgeCount(), map.ring(0).EdgeCount());
  // A map without steps is its own view, joins included.
  const Map box = ParseMap(testing::kBoxMapYaml, "box.yaml");
  const HallwayView v(box);
  EXPECT_EQ(v.view().EdgeCount(), box.EdgeCount());
  ASSERT_EQ(v.view().joins().size(), 1u);
  EXPECT_EQ(v.view().joins()[0].to_node, 0);
}

TEST(HallwayViewTest, EngineeringBuildingPilastersCollapse) {
  const Map eb = LoadMap(std::string(STICKREP_SOURCE_DIR) + "/maps/engineering_building_3f.yaml");
  const HallwayView view(eb);
  // 90 walls of 8, 13 and 27 in lie between opposite corners, 3 of them beside a join; all
  // go. The 46 in and deeper ones are corners.
  EXPECT_EQ(view.steps_removed(), 90);
  // The join beside the pilaster at wing1_corridor node 45 now names the view node that
  // begins the merged wall (original edges 41-45).
  const int ring = eb.FindRing("wing1_corridor");
  const int merged = view.ViewEdge(ring, 44);
  EXPECT_EQ(view.ViewEdge(ring, 41), merged);
  EXPECT_EQ(view.ViewEdge(ring, 45), merged);
  bool found = false;
  for (const Join& j : view.view().joins()) {
    if (j.to_ring == "wing1_corridor" && j.ring == "wing3_corridor") {
      found = true;
      EXPECT_EQ(j.to_node, merged);
    }
  }
  EXPECT_TRUE(found);
  int members = 0;  // every original edge lies in exactly one view edge
  for (int r = 0; r < eb.RingCount(); ++r)
    for (int e = 0; e < view.view().ring(r).EdgeCount(); ++e)
      members += static_cast<int>(view.OriginalEdges(r, e).size());
  EXPECT_EQ(members, eb.EdgeCount());
  EXPECT_LT(view.view().EdgeCount(), eb.EdgeCount() - 90);
  for (int r = 0; r < eb.RingCount(); ++r) {
    double a = 0, b = 0;
    for (const Edge& e : eb.ring(r).edges) a += e.metric_in;
    for (const Edge& e : view.view().ring(r).edges) b += e.metric_in;
    EXPECT_GT(a, b);  // the steps' lengths run across the hallway, not along it
  }
}

// Map format 2 on an open side: a wall curved through 30 deg as three chords (bends of
// 10 deg), an opening, a 120 deg corner (turned like any convex corner) and a 150 deg one
// (followed: 30 deg).
const char* kBends = R"(stickrep_map: 2
name: bends
rings:
  - id: side
    closed: false
    path:
      - node: {angle_deg: 180, xyz_in: [0, 0, 0]}
      - edge: {type: hallway, metric_in: 100}
      - node: {angle_deg: 170, xyz_in: [100, 0, 0]}
      - edge: {type: hallway, metric_in: 50}
      - node: {angle_deg: 170, xyz_in: [149.240, -8.682, 0]}
      - edge: {type: hallway, metric_in: 50}
      - node: {angle_deg: 170, xyz_in: [196.225, -25.783, 0]}
      - edge: {type: hallway, metric_in: 50}
      - node: {angle_deg: 180, xyz_in: [239.526, -50.783, 0]}
      - edge: {type: opening, metric_in: 80}
      - node: {angle_deg: 180, xyz_in: [308.808, -90.783, 0]}
      - edge: {type: hallway, metric_in: 40}
      - node: {angle_deg: 180, xyz_in: [343.449, -110.783, 0]}
      - edge: {type: doorway, width_in: 36}
      - node: {angle_deg: 120, xyz_in: [374.626, -128.783, 0]}
      - edge: {type: hallway, metric_in: 60}
      - node: {angle_deg: 150, xyz_in: [374.626, -188.783, 0]}
      - edge: {type: hallway, metric_in: 60}
      - node: {angle_deg: 180, xyz_in: [344.626, -240.745, 0]}
)";

TEST(HallwayViewTest, ShallowBendsAndOpeningsAreOneWallAndCornersAreTurns) {
  const Map map = ParseMap(kBends, "bends.yaml");
  const HallwayView view(map);
  const Ring& r = view.view().ring(0);
  // wall 100+50+50+50+80+40 | door 36 | wall 60+60
  ASSERT_EQ(r.EdgeCount(), 3);
  EXPECT_TRUE(r.edges[0].IsWall());
  EXPECT_DOUBLE_EQ(r.edges[0].metric_in, 370.0);
  EXPECT_TRUE(r.edges[1].IsDoor());
  EXPECT_DOUBLE_EQ(r.edges[2].metric_in, 120.0);
  EXPECT_DOUBLE_EQ(r.nodes[2].angle_deg, 90.0);  // 120 deg: the follower turns toward the wall
  EXPECT_EQ(view.OriginalEdges(0, 0), (std::vector<int>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(view.OriginalEdges(0, 2), (std::vector<int>{7, 8}));
  // Places map back through the merged chords and the opening.
  const HallwayView::Place p = view.ToOriginal(0, 0, +1, 260.0);
  EXPECT_EQ(p.edge, 4);
  EXPECT_DOUBLE_EQ(p.offset_in, 10.0);
  // With bends kept, every chord is its own wall and the 150 deg corner a turn.
  const HallwayView sharp(map, HallwayViewConfig{36.0, 5.0, {}});
  EXPECT_EQ(sharp.view().ring(0).EdgeCount(), 7);
  EXPECT_DOUBLE_EQ(sharp.view().ring(0).nodes[6].angle_deg, 90.0);
}

}  // namespace
}  // namespace stickrep::map
