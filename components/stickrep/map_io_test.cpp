#include "stickrep/map_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "common/input_error.h"
#include "stickrep/test_maps.h"

namespace stickrep::map {
namespace {

using testing::EditedBoxMap;
using testing::kBoxMapYaml;
using testing::kCorridorMapYaml;
using testing::LineOf;

InputError ParseError(const std::string& text) {
  try {
    ParseMap(text, "bad.yaml");
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "the map was accepted";
  return InputError("", 0, "", "");
}

TEST(MapIoTest, LoadsRingsEdgesNodesAndJoins) {
  const Map map = ParseMap(kBoxMapYaml, "box.yaml");
  ASSERT_EQ(map.RingCount(), 2);
  EXPECT_EQ(map.EdgeCount(), 8);
  const Ring& box = map.ring(0);
  EXPECT_TRUE(box.closed);
  EXPECT_EQ(box.EdgeCount(), 6);
  EXPECT_EQ(box.NodeCount(), 6);
  EXPECT_TRUE(box.edges[1].IsDoor());
  EXPECT_EQ(*box.edges[1].door_class, DoorClass::k36);
  EXPECT_DOUBLE_EQ(box.edges[1].metric_in, 36.0);
  EXPECT_EQ(box.edges[1].pattern, "poster");
  EXPECT_EQ(box.edges[1].prototype, Prototype::kDoorjam);
  EXPECT_DOUBLE_EQ(box.nodes[3].angle_deg, 90.0);
  EXPECT_DOUBLE_EQ(box.nodes[4].y_in, 0.0);
  const Ring& strip = map.ring(1);
  EXPECT_FALSE(strip.closed);
  EXPECT_EQ(strip.NodeCount(), 3);
  EXPECT_TRUE(strip.nodes[0].artificial);
  ASSERT_EQ(map.joins().size(), 1u);
  EXPECT_EQ(map.joins()[0].to_ring, "box");
}

TEST(MapIoTest, WrittenMapReadsBackToTheSameText) {
  const Map map = ParseMap(kBoxMapYaml, "box.yaml");
  const std::string text = WriteMapYaml(map);
  const Map again = ParseMap(text, "again.yaml");
  EXPECT_EQ(WriteMapYaml(again), text);
  EXPECT_EQ(again.EdgeCount(), map.EdgeCount());
}

TEST(MapIoTest, MalformedYamlIsReportedWithItsLine) {
  const InputError e = ParseError("stickrep_map: 1\nname: box\nrings: [ {id: a\n");
  EXPECT_GT(e.line(), 0);
  EXPECT_NE(e.reason().find("malformed YAML"), std::string::npos);
}

TEST(MapIoTest, MissingKeyNamesTheKey) {
  const std::string text = EditedBoxMap("    closed: true\n", "");
  const InputError e = ParseError(text);
  EXPECT_EQ(e.key(), "rings[0].closed");
  EXPECT_NE(e.reason().find("missing"), std::string::npos);
}

TEST(MapIoTest, NegativeWallLengthIsRejectedAtItsLine) {
  const std::string text = EditedBoxMap("metric_in: 24}", "metric_in: -24}");
  const InputError e = ParseError(text);
  EXPECT_EQ(e.line(), LineOf(text, "metric_in: -24"));
  EXPECT_NE(e.reason().find("> 0"), std::string::npos);
}

TEST(MapIoTest, ZeroWallLengthIsRejected) {
  const InputError e = ParseError(EditedBoxMap("metric_in: 24}", "metric_in: 0}"));
  EXPECT_NE(e.reason().find("> 0"), std::string::npos);
}

TEST(MapIoTest, IllegalDoorClassIsRejected) {
  const std::string text = EditedBoxMap("class: \"36\"", "class: \"34\"");
  const InputError e = ParseError(text);
  EXPECT_EQ(e.line(), LineOf(text, "class: \"34\""));
  EXPECT_NE(e.reason().find("not a legal door width"), std::string::npos);
}

TEST(MapIoTest, DoorMetricMustEqualItsClassWidth) {
  const InputError e = ParseError(EditedBoxMap("class: \"36\"", "class: \"36\", metric_in: 40"));
  EXPECT_NE(e.reason().find("36 in wide"), std::string::npos);
}

TEST(MapIoTest, DanglingJoinIsRejected) {
  const std::string text = EditedBoxMap("to_ring: box", "to_ring: nowhere");
  const InputError e = ParseError(text);
  EXPECT_EQ(e.line(), LineOf(text, "to_ring: nowhere"));
  EXPECT_NE(e.reason().find("no ring with id 'nowhere'"), std::string::npos);
}

TEST(MapIoTest, JoinAtANodeThatIsNotArtificialIsRejected) {
  const InputError e = ParseError(EditedBoxMap("{ring: strip, node: 0", "{ring: strip, node: 1"));
  EXPECT_NE(e.reason().find("not artificial"), std::string::npos);
}

TEST(MapIoTest, JoinNodeOutOfRangeIsRejected) {
  const InputError e = ParseError(EditedBoxMap("to_node: 0}", "to_node: 6}"));
  EXPECT_NE(e.reason().find("outside"), std::string::npos);
}

TEST(MapIoTest, UnknownKeyIsRejected) {
  const std::string text = EditedBoxMap("metric_in: 40}", "metric_in: 40, colour: red}");
  const InputError e = ParseError(text);
  EXPECT_EQ(e.line(), LineOf(text, "colour"));
  EXPECT_NE(e.reason().find("unknown key"), std::string::npos);
}

TEST(MapIoTest, AngleOutOfRangeIsRejected) {
  const InputError e = ParseError(
      EditedBoxMap("angle_deg: 90, xyz_in: [100, 0, 0]", "angle_deg: 400, xyz_in: [100, 0, 0]"));
  EXPECT_NE(e.reason().find("outside [0, 360]"), std::string::npos);
}

TEST(MapIoTest, DuplicateRingIdIsRejected) {
  const InputError e = ParseError(EditedBoxMap("  - id: strip", "  - id: box"));
  EXPECT_NE(e.reason().find("used by an earlier ring"), std::string::npos);
}

TEST(MapIoTest, ClosedRingThatDoesNotCloseIsRejected) {
  const InputError e = ParseError(EditedBoxMap("xyz_in: [0, 0, 0]}", "xyz_in: [0, 20, 0]}"));
  EXPECT_NE(e.reason().find("nodes are"), std::string::npos);
}

TEST(MapIoTest, OpenRingMustEndWithANode) {
  const std::string text = EditedBoxMap("      - node: {angle_deg: 180, xyz_in: [82, 200, 0]}\n", "");
  const InputError e = ParseError(text);
  EXPECT_NE(e.reason().find("open ring ends with a node"), std::string::npos);
}

TEST(MapIoTest, NodesAndEdgesMustAlternate) {
  const InputError e = ParseError(EditedBoxMap("      - edge: {type: hallway, metric_in: 50}\n",
                                         "      - edge: {type: hallway, metric_in: 25}\n      - "
                                         "edge: {type: hallway, metric_in: 25}\n"));
  EXPECT_NE(e.reason().find("alternate"), std::string::npos);
}

TEST(MapIoTest, UnknownEdgeTypeIsRejected) {
  const InputError e =
      ParseError(EditedBoxMap("type: hallway, metric_in: 40", "type: window, metric_in: 40"));
  EXPECT_NE(e.reason().find("unknown edge type"), std::string::npos);
}

TEST(MapIoTest, WrongFormatVersionIsRejected) {
  EXPECT_EQ(ParseError(EditedBoxMap("stickrep_map: 1", "stickrep_map: 3")).key(), "stickrep_map");
  EXPECT_EQ(ParseError(EditedBoxMap("stickrep_map: 1", "stickrep_map: 0")).key(), "stickrep_map");
}


TEST(MapIoTest, Format2KeepsMeasuredDoorWidthsOpeningsAndCorridorOutlines) {
  const Map map = ParseMap(kCorridorMapYaml, "corridor.yaml");
  const Ring& c = map.ring(0);
  EXPECT_EQ(c.outline, Outline::kCorridor);
  EXPECT_THAT(c.width_in, ::testing::Optional(96.0));
  // 53 in fits no single class: the nearest, within the tolerance, is the 60 in double.
  EXPECT_EQ(*c.edges[1].door_class, DoorClass::k30_30);
  EXPECT_DOUBLE_EQ(c.edges[1].metric_in, 53.0);
  EXPECT_TRUE(c.edges[3].IsOpening());
  EXPECT_EQ(*c.edges[7].door_class, DoorClass::k32);
  EXPECT_DOUBLE_EQ(c.edges[7].metric_in, 34.0);
  // Written back as format 2, and read again unchanged.
  const std::string text = WriteMapYaml(map);
  EXPECT_NE(text.find("stickrep_map: 2"), std::string::npos);
  EXPECT_NE(text.find("outline: corridor"), std::string::npos);
  EXPECT_EQ(WriteMapYaml(ParseMap(text, "again.yaml")), text);
  // A format 1 map is still written as format 1.
  EXPECT_NE(WriteMapYaml(ParseMap(kBoxMapYaml, "box.yaml")).find("stickrep_map: 1"),
            std::string::npos);
}

TEST(MapIoTest, Format2MistakesNameTheKey) {
  auto edited = [](const std::string& from, const std::string& to) {
    std::string text = kCorridorMapYaml;
    return text.replace(text.find(from), from.size(), to);
  };
  // 90 in is no door: the message points at openings.
  InputError e = ParseError(edited("width_in: 53", "width_in: 90"));
  EXPECT_EQ(e.key(), "rings[0].path[3].edge.width_in");
  EXPECT_NE(std::string(e.what()).find("opening"), std::string::npos) << e.what();
  // A class given with a width far from it.
  e = ParseError(edited("class: \"32\", width_in: 34", "class: \"32\", width_in: 50"));
  EXPECT_NE(std::string(e.what()).find("cannot be 50 in wide"), std::string::npos) << e.what();
  e = ParseError(edited("outline: corridor", "outline: both"));
  EXPECT_NE(std::string(e.what()).find("side, corridor"), std::string::npos) << e.what();
  e = ParseError(edited("closed: true", "closed: false"));  // and the path ends with an edge
  EXPECT_EQ(e.line(), 6);
  // Format 2 features in a format 1 file.
  e = ParseError(edited("stickrep_map: 2", "stickrep_map: 1"));
  EXPECT_NE(std::string(e.what()).find("format 2"), std::string::npos) << e.what();
  e = ParseError(EditedBoxMap("{type: hallway, metric_in: 24}", "{type: opening, metric_in: 24}"));
  EXPECT_NE(std::string(e.what()).find("format 2"), std::string::npos) << e.what();
}

TEST(MapIoTest, MissingFileIsAnInputError) {
  EXPECT_THROW(LoadMap(::testing::TempDir() + "no_such_map.yaml"), InputError);
}

}  // namespace
}  // namespace stickrep::map
