#include "stickrep/hallway_view.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "stickrep/map_io.h"
#include "stickrep/sequence_matcher.h"
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
  // wall 100+50+50+50+80+40 | door 36 | wall 60+60, as the odometer travels them 60 in out
  // from the wall (the default 120 in hallway): outside each 10 deg bend 2 x 60 tan(5 deg)
  // = 10.50 in more, outside the 150 deg one 2 x 60 tan(15 deg) = 32.15 in more.
  ASSERT_EQ(r.EdgeCount(), 3);
  EXPECT_TRUE(r.edges[0].IsWall());
  EXPECT_NEAR(r.edges[0].metric_in, 370.0 + 3 * 10.4985, 0.01);
  EXPECT_TRUE(r.edges[1].IsDoor());
  EXPECT_NEAR(r.edges[2].metric_in, 120.0 + 32.1539, 0.01);
  EXPECT_DOUBLE_EQ(r.nodes[2].angle_deg, 90.0);  // 120 deg: the follower turns toward the wall
  EXPECT_EQ(view.OriginalEdges(0, 0), (std::vector<int>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(view.OriginalEdges(0, 2), (std::vector<int>{7, 8}));
  // Places map back through the merged chords and the opening, the odometer's extra travel
  // outside the bends spread along the wall: 260 in of wall is 260 x 401.50 / 370 travelled.
  const HallwayView::Place p = view.ToOriginal(0, 0, +1, 260.0 * r.edges[0].metric_in / 370.0);
  EXPECT_EQ(p.edge, 4);
  EXPECT_NEAR(p.offset_in, 10.0, 1e-9);
  const HallwayView::Place end = view.ToOriginal(0, 0, +1, r.edges[0].metric_in);
  EXPECT_EQ(end.edge, 5);
  EXPECT_NEAR(end.offset_in, 40.0, 1e-9);
  // The wall bent the other way (toward the free space): the base passes inside the bends.
  std::string inside = kBends;
  for (std::size_t at; (at = inside.find("angle_deg: 170")) != std::string::npos;) {
    inside.replace(at, 14, "angle_deg: 190");
  }
  EXPECT_NEAR(HallwayView(ParseMap(inside, "inside.yaml")).view().ring(0).edges[0].metric_in,
              370.0 - 3 * 10.4985, 0.01);
  // With bends kept, every chord is its own wall and the 150 deg corner a turn.
  const HallwayView sharp(map, HallwayViewConfig{36.0, 5.0, {}});
  EXPECT_EQ(sharp.view().ring(0).EdgeCount(), 7);
  EXPECT_DOUBLE_EQ(sharp.view().ring(0).nodes[6].angle_deg, 90.0);
}

// A corridor outline 88 in wide: open at its west end onto another corridor (an opening
// between two 270 deg corners), a side opening 96 in wide in its north wall.
const char* kOpenEnded = R"(stickrep_map: 2
name: open_ended
rings:
  - id: wing
    closed: true
    outline: corridor
    width_in: 88
    path:
      - node: {angle_deg: 270, xyz_in: [0, 0, 0]}
      - edge: {type: opening, metric_in: 88}
      - node: {angle_deg: 270, xyz_in: [0, 88, 0]}
      - edge: {type: hallway, metric_in: 200}
      - node: {angle_deg: 180, xyz_in: [200, 88, 0]}
      - edge: {type: opening, metric_in: 96}
      - node: {angle_deg: 180, xyz_in: [296, 88, 0]}
      - edge: {type: hallway, metric_in: 204}
      - node: {angle_deg: 90, xyz_in: [500, 88, 0]}
      - edge: {type: hallway, metric_in: 88}
      - node: {angle_deg: 90, xyz_in: [500, 0, 0]}
      - edge: {type: hallway, metric_in: 500}
)";

TEST(HallwayViewTest, ACorridorsOpenEndStaysAnOpeningWhereASideOpeningIsWall) {
  const Map map = ParseMap(kOpenEnded, "open_ended.yaml");
  EXPECT_TRUE(IsOpenEnd(map.ring(0).edges[0], 270.0, 270.0));
  EXPECT_FALSE(IsOpenEnd(map.ring(0).edges[2], 180.0, 180.0));
  EXPECT_FALSE(IsOpenEnd(map.ring(0).edges[0], 90.0, 270.0));  // a step, not an end
  EXPECT_FALSE(IsOpenEnd(map.ring(0).edges[1], 270.0, 270.0));  // a wall
  const HallwayView view(map);
  const Ring& r = view.view().ring(0);
  // open end 88 | wall 200 + 96 + 204 | end wall 88 | wall 500
  ASSERT_EQ(r.EdgeCount(), 4);
  EXPECT_TRUE(r.edges[0].IsOpening());
  EXPECT_TRUE(r.edges[1].IsWall());
  EXPECT_DOUBLE_EQ(r.edges[1].metric_in, 500.0);
  const MatchIndex index(view.view());
  EXPECT_TRUE(index.open_end(0));
  EXPECT_EQ(index.code(0), kWallCode);
  EXPECT_FALSE(index.open_end(1));
}

// One side of an 88 in corridor: a 36 in door, a 44 in door and a 72 in double door.
const char* kNarrowCorridor = R"(stickrep_map: 2
name: narrow
rings:
  - id: side
    closed: false
    width_in: 88
    path:
      - node: {angle_deg: 180, xyz_in: [0, 0, 0]}
      - edge: {type: hallway, metric_in: 100}
      - node: {angle_deg: 180, xyz_in: [100, 0, 0]}
      - edge: {type: doorway, width_in: 36}
      - node: {angle_deg: 180, xyz_in: [136, 0, 0]}
      - edge: {type: hallway, metric_in: 50}
      - node: {angle_deg: 180, xyz_in: [186, 0, 0]}
      - edge: {type: doorway, width_in: 44}
      - node: {angle_deg: 180, xyz_in: [230, 0, 0]}
      - edge: {type: hallway, metric_in: 70}
      - node: {angle_deg: 180, xyz_in: [300, 0, 0]}
      - edge: {type: doorway, class: "36/36"}
      - node: {angle_deg: 180, xyz_in: [372, 0, 0]}
      - edge: {type: hallway, metric_in: 28}
      - node: {angle_deg: 180, xyz_in: [400, 0, 0]}
)";

std::vector<double> Metrics(const Ring& r) {
  std::vector<double> m;
  for (const Edge& e : r.edges) m.push_back(e.IsDoor() ? -e.metric_in : e.metric_in);
  return m;
}

TEST(HallwayViewTest, ADoorTooWideForTheCameraFromTheAxisIsWall) {
  const Map map = ParseMap(kNarrowCorridor, "narrow.yaml");
  HallwayViewConfig config;
  // Without the camera every door is a door (doors negative).
  EXPECT_EQ(Metrics(HallwayView(map, config).view().ring(0)),
            (std::vector<double>{100, -36, 50, -44, 70, -72, 28}));
  // 44 in from the wall a 55.8 deg view covers 46.6 in; with 10 in for the casings and the
  // frames, a 36 in door and each 36 in leaf are seen, the 44 in door never: it is wall,
  // one wall with the walls either side (50 + 44 + 70).
  config.camera_fov_deg = 55.817;
  config.door_view_margin_in = 10.0;
  const HallwayView narrow(map, config);
  EXPECT_EQ(Metrics(narrow.view().ring(0)), (std::vector<double>{100, -36, 164, -72, 28}));
  EXPECT_EQ(narrow.OriginalEdges(0, 2), (std::vector<int>{2, 3, 4}));
  // The same corridor 120 in wide (the ring's width unknown: the settings' default): the
  // view covers 63.6 in and every door is seen.
  std::string text = kNarrowCorridor;
  text.erase(text.find("    width_in: 88\n"), std::string("    width_in: 88\n").size());
  config.hallway_width_in = 120.0;
  EXPECT_EQ(Metrics(HallwayView(ParseMap(text, "wide.yaml"), config).view().ring(0)),
            (std::vector<double>{100, -36, 50, -44, 70, -72, 28}));
}

// One side of a hallway with a 48 in deep alcove holding two 36 in doors (its back 96 in
// long), then two blocks standing 48 in out with an 80 in wall between them.
const char* kAlcoveAndBlocks = R"(stickrep_map: 2
name: alcove
rings:
  - id: alcove
    closed: false
    path:
      - node: {angle_deg: 180, xyz_in: [0, 0, 0]}
      - edge: {type: hallway, metric_in: 94}
      - node: {angle_deg: 90, xyz_in: [94, 0, 0]}
      - edge: {type: hallway, metric_in: 48}
      - node: {angle_deg: 270, xyz_in: [94, 48, 0]}
      - edge: {type: hallway, metric_in: 6}
      - node: {angle_deg: 180, xyz_in: [100, 48, 0]}
      - edge: {type: doorway, class: "36"}
      - node: {angle_deg: 180, xyz_in: [136, 48, 0]}
      - edge: {type: hallway, metric_in: 12}
      - node: {angle_deg: 180, xyz_in: [148, 48, 0]}
      - edge: {type: doorway, class: "36"}
      - node: {angle_deg: 180, xyz_in: [184, 48, 0]}
      - edge: {type: hallway, metric_in: 6}
      - node: {angle_deg: 270, xyz_in: [190, 48, 0]}
      - edge: {type: hallway, metric_in: 48}
      - node: {angle_deg: 90, xyz_in: [190, 0, 0]}
      - edge: {type: hallway, metric_in: 84}
      - node: {angle_deg: 180, xyz_in: [274, 0, 0]}
  - id: blocks
    closed: false
    path:
      - node: {angle_deg: 180, xyz_in: [0, 500, 0]}
      - edge: {type: hallway, metric_in: 20}
      - node: {angle_deg: 270, xyz_in: [20, 500, 0]}
      - edge: {type: hallway, metric_in: 48}
      - node: {angle_deg: 90, xyz_in: [20, 452, 0]}
      - edge: {type: hallway, metric_in: 18}
      - node: {angle_deg: 90, xyz_in: [38, 452, 0]}
      - edge: {type: hallway, metric_in: 48}
      - node: {angle_deg: 270, xyz_in: [38, 500, 0]}
      - edge: {type: hallway, metric_in: 80}
      - node: {angle_deg: 270, xyz_in: [118, 500, 0]}
      - edge: {type: hallway, metric_in: 48}
      - node: {angle_deg: 90, xyz_in: [118, 452, 0]}
      - edge: {type: hallway, metric_in: 18}
      - node: {angle_deg: 90, xyz_in: [136, 452, 0]}
      - edge: {type: hallway, metric_in: 48}
      - node: {angle_deg: 270, xyz_in: [136, 500, 0]}
      - edge: {type: hallway, metric_in: 20}
      - node: {angle_deg: 180, xyz_in: [156, 500, 0]}
)";

TEST(HallwayViewTest, AnAlcoveIsPassedStraightAndBlocksAreTurnedAt) {
  const Map map = ParseMap(kAlcoveAndBlocks, "alcove.yaml");
  const HallwayView view(map);
  // The alcove's sides go: one wall with two doors at its back (94 + 6, 12, 6 + 84).
  EXPECT_EQ(view.steps_removed(), 2);
  const Ring& alcove = view.view().ring(0);
  EXPECT_EQ(Metrics(alcove), (std::vector<double>{100, -36, 12, -36, 90}));
  for (const Node& node : alcove.nodes) EXPECT_DOUBLE_EQ(node.angle_deg, 180.0);
  EXPECT_EQ(view.OriginalEdges(0, 0), (std::vector<int>{0, 1, 2}));
  // The wall between the blocks is not an alcove: the faces either side of it (18 + 18 in)
  // are shorter than it, the follower tracks it and turns at each block.
  EXPECT_EQ(view.view().ring(1).EdgeCount(), 9);
  // A back longer than the follower holds its track across: the alcove is turned into.
  HallwayViewConfig short_recess;
  short_recess.max_recess_in = 90.0;
  EXPECT_EQ(HallwayView(map, short_recess).view().ring(0).EdgeCount(), 9);
}

}  // namespace
}  // namespace stickrep::map
