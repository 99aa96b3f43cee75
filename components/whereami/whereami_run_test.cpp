// The closed-loop Where-am-I run without middleware: the processes' logic on the small test
// map, judged against the simulated truth.
#include "whereami/whereami_run.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "common/input_error.h"
#include "whereami/whereami_report.h"

namespace stickrep::whereami {
namespace {

const std::string kSmallMap = std::string(STICKREP_SOURCE_DIR) + "/test/maps/wing1_corridor.yaml";

const RunSetup& SmallMapSetup() {
  static const RunSetup setup = LoadRunSetup("", kSmallMap);
  return setup;
}

TEST(WhereAmIRunTest, SeededStartsOnTheSmallMapRecoverTheTruePose) {
  for (std::uint64_t seed : {5, 6, 7, 8}) {
    RunOptions o;
    o.seed = seed;
    const RunResult r = RunWhereAmI(SmallMapSetup(), o);
    ASSERT_TRUE(r.first.has_value()) << "seed " << seed << ": " << r.ended;
    EXPECT_TRUE(r.first->correct) << "seed " << seed << ": localized on edge " << r.first->edge
                                  << ", truth edge " << r.first->truth_edge;
    EXPECT_EQ(r.collisions, 0) << "seed " << seed;
    // Inside the navigation envelope of §6.4.2 on straight runs after aligning.
    EXPECT_LE(r.max_offset_in, 12.0) << "seed " << seed;
    EXPECT_LE(r.max_heading_deg, 7.5 + 2.5) << "seed " << seed;
  }
}

TEST(WhereAmIRunTest, TheSameSeedGivesTheSameRun) {
  RunOptions o;
  o.seed = 9;
  const RunResult a = RunWhereAmI(SmallMapSetup(), o);
  const RunResult b = RunWhereAmI(SmallMapSetup(), o);
  ASSERT_TRUE(a.first && b.first);
  EXPECT_EQ(a.start, b.start);
  EXPECT_EQ(a.first->edge, b.first->edge);
  EXPECT_EQ(a.first->edges_sensed, b.first->edges_sensed);
  EXPECT_DOUBLE_EQ(a.first->distance_ft, b.first->distance_ft);
  EXPECT_EQ(a.frames, b.frames);
}

TEST(WhereAmIRunTest, AKidnappedRobotIsNoticedAndRecovers) {
  RunOptions o;
  o.seed = 10;
  o.kidnap_after_s = 3.0;
  o.kidnap_jump_in = 2500.0;
  const RunResult r = RunWhereAmI(SmallMapSetup(), o);
  ASSERT_TRUE(r.first.has_value()) << r.ended;
  EXPECT_TRUE(r.kidnapped);
  EXPECT_TRUE(r.lost_detected);
  ASSERT_TRUE(r.second.has_value()) << r.ended;
  EXPECT_TRUE(r.second->correct) << "edge " << r.second->edge << ", truth " << r.second->truth_edge;
}

TEST(WhereAmIRunTest, MeasuringCountsTheDoorsAndWallsPassed) {
  RunOptions o;
  o.seed = 11;
  o.measure_ft = 150.0;
  const RunResult r = RunWhereAmI(SmallMapSetup(), o);
  const EdgeErrorCounts& c = r.errors;
  // 150 ft of a corridor with a door every 7 ft or so, less the first 20 ft.
  EXPECT_GT(c.true_doors, 10);
  EXPECT_GT(c.true_walls, 10);
  EXPECT_EQ(c.correct + c.missized + c.missed, c.true_doors);
  EXPECT_GT(c.correct, c.true_doors / 2);
  const recovery::ErrorModel m = c.ToModel("test");
  EXPECT_NO_THROW(m.Validate());
}

TEST(WhereAmIToolTest, UnknownRingIsBadInput) {
  ToolOptions o;
  o.map_file = kSmallMap;
  o.rings = {"no_such_ring"};
  o.runs = 1;
  std::ostringstream out, err;
  EXPECT_EQ(RunTool(o, out, err), kExitBadInput);
  EXPECT_NE(err.str().find("no ring 'no_such_ring'"), std::string::npos) << err.str();
}

}  // namespace
}  // namespace stickrep::whereami
