// Checks over the committed maps under maps/: they load, the generators reproduce them
// byte for byte from the seed in their header, and the Engineering Building keeps the
// census tables it was built to.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "stickrep/ambiguity.h"
#include "stickrep/census.h"
#include "map_tool/map_generators.h"
#include "stickrep/map_io.h"
#include "stickrep/paper_reference.h"

namespace stickrep::map {
namespace {

std::string MapPath(const std::string& name) {
  return std::string(STICKREP_SOURCE_DIR) + "/maps/" + name + ".yaml";
}

std::string ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

class ShippedMapTest : public ::testing::TestWithParam<std::string> {};

TEST_P(ShippedMapTest, Validates) {
  const Map map = LoadMap(MapPath(GetParam()));
  EXPECT_EQ(map.info().name, GetParam());
  EXPECT_TRUE(map.info().seed.has_value());
}

TEST_P(ShippedMapTest, RegeneratesByteForByteFromItsSeed) {
  const Map committed = LoadMap(MapPath(GetParam()));
  const Map again = GenerateDomain(GetParam(), *committed.info().seed);
  EXPECT_EQ(WriteMapYaml(again), ReadFile(MapPath(GetParam())));
}

TEST_P(ShippedMapTest, EveryStartBecomesUniqueWithoutSensingError) {
  const AmbiguityResult r = AnalyseAmbiguity(LoadMap(MapPath(GetParam())));
  EXPECT_EQ(r.unique, static_cast<int>(r.starts.size()));
}

INSTANTIATE_TEST_SUITE_P(AllDomains, ShippedMapTest,
                         ::testing::Values("engineering_building_3f", "wells_hall_7f",
                                           "wells_hall_7f_modified", "regular_polygon_46",
                                           "storefront"));

TEST(EngineeringBuildingTest, MatchesTables61To63ExactlyAndTable69) {
  const Census c = ComputeCensus(LoadMap(MapPath("engineering_building_3f")));
  EXPECT_EQ(c.pairs, paper::kPairs);
  EXPECT_EQ(c.wall_census, paper::kWallCensus);
  EXPECT_EQ(c.door_census, paper::kDoorCensus);
  EXPECT_EQ(c.walls, 431);
  EXPECT_EQ(c.leaf_edges, 680);
  EXPECT_NEAR(c.mean_leaf_metric_in, paper::kEngineeringMeanEdgeMetricIn, 0.01);
}

TEST(EngineeringBuildingTest, NoErrorAmbiguityIsNearTable622) {
  const AmbiguityResult r = AnalyseAmbiguity(LoadMap(MapPath("engineering_building_3f")));
  EXPECT_NEAR(r.mean_edges, paper::kNoErrorEdges[0].edges, 0.5);
}

}  // namespace
}  // namespace stickrep::map
