#include "localizer/map_msg.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "localizationPubSubTypes.h"
#include "stickrep/map_io.h"
#include "stickrep/test_maps.h"

namespace stickrep::localizer {
namespace {

// Every shipped map file (maps/*.yaml).
std::vector<std::string> ShippedMaps() {
  std::vector<std::string> paths;
  for (const auto& entry : std::filesystem::directory_iterator(STICKREP_SOURCE_DIR "/maps")) {
    if (entry.path().extension() == ".yaml") paths.push_back(entry.path().string());
  }
  return paths;
}

// What the message carries of `a` is in `b` too.
void ExpectSameRings(const map::Map& a, const map::Map& b) {
  EXPECT_EQ(a.info().name, b.info().name);
  ASSERT_EQ(a.RingCount(), b.RingCount());
  for (int r = 0; r < a.RingCount(); ++r) {
    const map::Ring& x = a.ring(r);
    const map::Ring& y = b.ring(r);
    SCOPED_TRACE("ring " + x.id);
    EXPECT_EQ(x.id, y.id);
    EXPECT_EQ(x.closed, y.closed);
    ASSERT_EQ(x.EdgeCount(), y.EdgeCount());
    ASSERT_EQ(x.NodeCount(), y.NodeCount());
    for (int i = 0; i < x.EdgeCount(); ++i) {
      EXPECT_EQ(x.edges[i].type, y.edges[i].type) << "edge " << i;
      EXPECT_DOUBLE_EQ(x.edges[i].metric_in, y.edges[i].metric_in) << "edge " << i;
      EXPECT_EQ(x.edges[i].door_class, y.edges[i].door_class) << "edge " << i;
      EXPECT_EQ(x.edges[i].pattern, y.edges[i].pattern) << "edge " << i;
      EXPECT_DOUBLE_EQ(x.nodes[i].angle_deg, y.nodes[i].angle_deg) << "node " << i;
      EXPECT_DOUBLE_EQ(x.nodes[i].x_in, y.nodes[i].x_in) << "node " << i;
      EXPECT_DOUBLE_EQ(x.nodes[i].y_in, y.nodes[i].y_in) << "node " << i;
    }
  }
}

TEST(MapMsgTest, EveryShippedMapComesBackWithItsRingsEdgesAndNodes) {
  const auto paths = ShippedMaps();
  ASSERT_GE(paths.size(), 5u);
  for (const std::string& path : paths) {
    SCOPED_TRACE(path);
    const map::Map original = map::LoadMap(path);
    const msgs::StickRepMap msg = ToMsg(original);
    const map::Map back = FromMsg(msg);
    ExpectSameRings(original, back);
    EXPECT_EQ(ToMsg(back), msg);
  }
}

TEST(MapMsgTest, OpeningsSurviveSerialization) {
  // science_hall_2f has openings (map format 2), which the IDL's EdgeKind does not name.
  const map::Map original = map::LoadMap(STICKREP_SOURCE_DIR "/maps/science_hall_2f.yaml");
  int openings = 0;
  for (const map::Ring& r : original.rings()) {
    for (const map::Edge& e : r.edges) openings += e.IsOpening() ? 1 : 0;
  }
  ASSERT_GT(openings, 0);
  msgs::StickRepMap msg = ToMsg(original);
  msgs::StickRepMapPubSubType support;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(support.getSerializedSizeProvider(&msg)());
  ASSERT_TRUE(support.serialize(&msg, &payload));
  msgs::StickRepMap received;
  ASSERT_TRUE(support.deserialize(&payload, &received));
  ExpectSameRings(original, FromMsg(received));
}

TEST(MapMsgTest, AnOpenRingsEndNodeLiesOneMetricAlongItsLastEdge) {
  const map::Map box = map::ParseMap(map::testing::kBoxMapYaml, "box.yaml");
  const map::Map back = FromMsg(ToMsg(box));
  const map::Ring& strip = back.ring(back.FindRing("strip"));
  ASSERT_FALSE(strip.closed);
  ASSERT_EQ(strip.NodeCount(), 3);
  EXPECT_NEAR(strip.nodes[2].x_in, 82.0, 1e-9);
  EXPECT_NEAR(strip.nodes[2].y_in, 200.0, 1e-9);
  // Joins are not in the message.
  EXPECT_TRUE(back.joins().empty());
}

TEST(MapMsgTest, AnOpenRingTurnsAtItsLastNodeByTheAdjacencyAngle) {
  msgs::StickRepMap msg;
  msg.name("turn");
  msgs::MapRing ring;
  ring.ring_id("l");
  ring.closed(false);
  msgs::MapEdge first;
  first.kind(msgs::EDGE_HALLWAY);
  first.metric_in(100.0);
  first.start_angle_deg(180.0);
  msgs::MapEdge second = first;
  second.metric_in(50.0);
  second.start_angle_deg(90.0);  // a convex corner: the wall turns right
  second.x_in(100.0);
  ring.edges({first, second});
  msg.rings({ring});
  const map::Map map = FromMsg(msg);
  const map::Ring& back = map.ring(0);
  ASSERT_EQ(back.NodeCount(), 3);
  EXPECT_NEAR(back.nodes[2].x_in, 100.0, 1e-9);
  EXPECT_NEAR(back.nodes[2].y_in, -50.0, 1e-9);
}

TEST(MapMsgTest, AMessageThatIsNoMapIsRefusedNamingTheEdge) {
  msgs::StickRepMap msg = ToMsg(map::ParseMap(map::testing::kBoxMapYaml, "box.yaml"));
  msg.rings()[0].edges()[1].door_class("31");
  try {
    FromMsg(msg);
    FAIL() << "a door of class 31 was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("ring 'box' edge 1"));
  }
  msg = ToMsg(map::ParseMap(map::testing::kBoxMapYaml, "box.yaml"));
  msg.rings()[1].edges()[0].kind(static_cast<msgs::EdgeKind>(9));
  EXPECT_THROW(FromMsg(msg), std::invalid_argument);
  msg.rings().clear();
  EXPECT_THROW(FromMsg(msg), std::invalid_argument);  // a map needs a ring
}

}  // namespace
}  // namespace stickrep::localizer
