#include "map_tool/floor_plan.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "common/input_error.h"
#include "stickrep/map_io.h"

namespace stickrep::map {
namespace {

// A corridor 96 in wide and 600 in long along +x, then 45 deg to the left for 300 in. On
// its right: a 53 in door, an alcove 60 in wide and 30 in deep with a 36 in door, a 90 in
// opening; on its left a pier 18 in wide standing 12 in out. One round column.
const char* kSource = R"(stickrep_floor: 1
name: test_floor
description: "floor plan test"
corridors:
  - id: main
    width_in: 96
    start: {xy_in: [0, 0], heading_deg: 0}
    path:
      - straight_in: 600
      - turn_deg: 45
      - straight_in: 300
    ends: {start: wall, end: opening}
    right:
      - {at_in: 50, door_in: 53}
      - {at_in: 200, alcove: {width_in: 60, depth_in: 30, doors: [{at_in: 12, door_in: 36}]}}
      - {at_in: 400, opening_in: 90}
    left:
      - {at_in: 300, pier: {width_in: 18, depth_in: 12}}
obstacles:
  - {id: column, circle: {centre_in: [300, 200], diameter_in: 20, sides: 12}}
)";

std::string Edited(const std::string& from, const std::string& to) {
  std::string text = kSource;
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

InputError BuildError(const std::string& text) {
  try {
    ParseFloorPlan(text, "bad.floor.yaml");
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "the floor plan was accepted";
  return InputError("", 0, "", "");
}

TEST(FloorPlanTest, BuildsAClosedCorridorOutlineWalkedWithTheWallOnTheRight) {
  const Map map = ParseFloorPlan(kSource, "test.floor.yaml");
  ASSERT_EQ(map.RingCount(), 1);
  const Ring& ring = map.ring(0);
  EXPECT_EQ(ring.outline, Outline::kCorridor);
  EXPECT_TRUE(ring.closed);
  EXPECT_EQ(ring.width_in.value_or(0.0), 96.0);
  // Free space on the left: the outline runs counter-clockwise (positive area).
  double area2 = 0.0;
  for (int i = 0; i < ring.NodeCount(); ++i) {
    const Node& a = ring.nodes[i];
    const Node& b = ring.nodes[(i + 1) % ring.NodeCount()];
    area2 += a.x_in * b.y_in - b.x_in * a.y_in;
  }
  EXPECT_GT(area2, 0.0);
  // Node angles sum as a simple polygon's: (n - 2) * 180 measured inside the free space
  // is 360 n - sum(angle) here, since angles are measured inside the solid.
  double sum = 0.0;
  for (const Node& n : ring.nodes) sum += n.angle_deg;
  EXPECT_NEAR(360.0 * ring.NodeCount() - sum, 180.0 * (ring.NodeCount() - 2), 1e-6);
  // The corridor's near end is a wall across, 96 in long, between two 270 deg corners.
  const Edge& end = ring.edges.back();
  EXPECT_TRUE(end.IsWall());
  EXPECT_NEAR(end.metric_in, 96.0, 1e-6);
  EXPECT_NEAR(ring.nodes.back().angle_deg, 270.0, 1e-6);
  EXPECT_NEAR(ring.nodes.front().angle_deg, 270.0, 1e-6);
}

TEST(FloorPlanTest, SetsDoorsOpeningsAlcovesAndPiersAtTheirStations) {
  const Ring ring = ParseFloorPlan(kSource, "test.floor.yaml").ring(0);
  // Right side in order: wall 50, door 53, wall, alcove (in 30, back wall 12 | door 36 |
  // 12, out 30), wall, opening 90, wall to the bend.
  ASSERT_GE(ring.EdgeCount(), 12);
  EXPECT_NEAR(ring.edges[0].metric_in, 50.0, 1e-6);
  ASSERT_TRUE(ring.edges[1].IsDoor());
  EXPECT_NEAR(ring.edges[1].metric_in, 53.0, 1e-6);
  EXPECT_EQ(*ring.edges[1].door_class, DoorClass::k30_30);
  EXPECT_NEAR(ring.edges[2].metric_in, 200.0 - 103.0, 1e-6);
  EXPECT_NEAR(ring.edges[3].metric_in, 30.0, 1e-6);  // into the alcove
  EXPECT_NEAR(ring.nodes[3].angle_deg, 90.0, 1e-6);  // the wall turns away: convex
  EXPECT_NEAR(ring.nodes[4].angle_deg, 270.0, 1e-6);
  EXPECT_NEAR(ring.edges[4].metric_in, 12.0, 1e-6);
  EXPECT_TRUE(ring.edges[5].IsDoor());
  EXPECT_NEAR(ring.edges[6].metric_in, 12.0, 1e-6);
  EXPECT_NEAR(ring.edges[7].metric_in, 30.0, 1e-6);  // out again
  EXPECT_NEAR(ring.edges[8].metric_in, 400.0 - 260.0, 1e-6);
  EXPECT_TRUE(ring.edges[9].IsOpening());
  EXPECT_NEAR(ring.edges[9].metric_in, 90.0, 1e-6);
  // The pier on the left stands into the corridor: the wall turns toward the free space
  // first (270), and the pier's face is 18 in.
  bool pier = false;
  for (int i = 0; i + 2 < ring.EdgeCount(); ++i) {
    if (std::abs(ring.edges[i].metric_in - 12.0) < 1e-6 &&
        std::abs(ring.edges[i + 1].metric_in - 18.0) < 1e-6 &&
        std::abs(ring.edges[i + 2].metric_in - 12.0) < 1e-6) {
      pier = true;
      EXPECT_NEAR(ring.nodes[i].angle_deg, 270.0, 1e-6);
      EXPECT_NEAR(ring.nodes[i + 1].angle_deg, 90.0, 1e-6);
    }
  }
  EXPECT_TRUE(pier);
  // The far end is an opening, and the 45 deg bend gives corners of 135 and 225 deg.
  int bends = 0;
  for (const Node& n : ring.nodes) {
    bends += std::abs(n.angle_deg - 135.0) < 1e-6 || std::abs(n.angle_deg - 225.0) < 1e-6;
  }
  EXPECT_EQ(bends, 2);
  int openings = 0;
  for (const Edge& e : ring.edges) openings += e.IsOpening();
  EXPECT_EQ(openings, 2);
}

TEST(FloorPlanTest, ColumnsBecomeObstaclesAndTheMapRoundTrips) {
  const Map map = ParseFloorPlan(kSource, "test.floor.yaml");
  ASSERT_EQ(map.obstacles().size(), 1u);
  EXPECT_EQ(map.obstacles()[0].id, "column");
  EXPECT_EQ(map.obstacles()[0].polygon_in.size(), 12u);
  EXPECT_NEAR(map.obstacles()[0].polygon_in[0][0], 310.0, 1e-6);
  const std::string yaml = WriteMapYaml(map);
  EXPECT_NE(yaml.find("stickrep_map: 2"), std::string::npos);
  EXPECT_NE(yaml.find("program: \"stickrep-map floor test.floor.yaml\""), std::string::npos);
  EXPECT_EQ(WriteMapYaml(ParseMap(yaml, "again.yaml")), yaml);
}

TEST(FloorPlanTest, MistakesNameFileLineKeyAndReason) {
  // A feature that runs past the bend.
  InputError e = BuildError(Edited("{at_in: 400, opening_in: 90}", "{at_in: 560, opening_in: 90}"));
  EXPECT_EQ(e.line(), 16);
  EXPECT_NE(std::string(e.what()).find("one straight stretch"), std::string::npos) << e.what();
  // Features that overlap.
  e = BuildError(Edited("{at_in: 400, opening_in: 90}", "{at_in: 230, opening_in: 90}"));
  EXPECT_NE(std::string(e.what()).find("overlaps"), std::string::npos) << e.what();
  // A door no class fits.
  e = BuildError(Edited("door_in: 53", "door_in: 90"));
  EXPECT_NE(std::string(e.what()).find("opening"), std::string::npos) << e.what();
  // An alcove door wider than the alcove's back wall.
  e = BuildError(Edited("{at_in: 12, door_in: 36}", "{at_in: 30, door_in: 36}"));
  EXPECT_NE(std::string(e.what()).find("back wall"), std::string::npos) << e.what();
  // A pier as deep as half the corridor.
  e = BuildError(Edited("depth_in: 12}", "depth_in: 48}"));
  EXPECT_NE(std::string(e.what()).find("centreline"), std::string::npos) << e.what();
  // Unknown keys, two kinds in one feature, a bad end.
  e = BuildError(Edited("straight_in: 300", "straigth_in: 300"));
  EXPECT_NE(std::string(e.what()).find("unknown path item"), std::string::npos) << e.what();
  e = BuildError(Edited("{at_in: 50, door_in: 53}", "{at_in: 50, door_in: 53, opening_in: 53}"));
  EXPECT_NE(std::string(e.what()).find("exactly one"), std::string::npos) << e.what();
  e = BuildError(Edited("end: opening", "end: door"));
  EXPECT_EQ(e.key(), "corridors[0].ends.end");
  e = BuildError(Edited("{at_in: 400, opening_in: 90}", "{at_in: 1000, opening_in: 90}"));
  EXPECT_NE(std::string(e.what()).find("beyond the corridor's end"), std::string::npos)
      << e.what();
}

// The shipped realistic maps are exactly what their sources build.
TEST(FloorPlanTest, ShippedMapsAreBuiltFromTheirSources) {
  for (const char* name : {"teaching_building_1f", "science_hall_2f"}) {
    const std::string dir = std::string(STICKREP_SOURCE_DIR) + "/maps/";
    const Map built = LoadFloorPlan(dir + "sources/" + name + ".floor.yaml");
    std::ifstream shipped(dir + name + ".yaml", std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(shipped)), {});
    EXPECT_EQ(WriteMapYaml(built), text)
        << name << ": regenerate with stickrep-map floor maps/sources/" << name
        << ".floor.yaml --out maps/" << name << ".yaml";
  }
}

}  // namespace
}  // namespace stickrep::map
