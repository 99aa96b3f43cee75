// The stickrep-whereami batch: seeds over worker threads, starts drawn again, runs that
// cannot be run, and the tool's bad input.
#include "whereami_tool/whereami_report.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "common/input_error.h"
#include "whereami/test_setup.h"

namespace stickrep::whereami {
namespace {

using testing::kSmallMap;
using testing::SmallMapSetup;

TEST(WhereAmIBatchTest, StartsAgainstAWallAreDrawnAgainAndLogged) {
  RunSetup setup = SmallMapSetup();
  // Up to 58 in off the axis of a 120 in hallway: some starts put the base against a wall.
  setup.virtual_robot.start_lateral_offset_max_in = 58.0;
  ToolOptions options;
  options.first_seed = 1;
  options.runs = 16;
  options.max_sim_s = 2.0;  // only the start matters here
  const std::vector<RunResult> results = RunSeeds(setup, options);
  int redraws = 0;
  for (const RunResult& r : results) {
    EXPECT_FALSE(r.failed) << "seed " << r.seed << ": " << r.ended;
    for (const std::string& why : r.start_redraws) {
      EXPECT_NE(why.find("against a wall"), std::string::npos) << why;
      EXPECT_NE(why.find("drawn again"), std::string::npos) << why;
    }
    redraws += static_cast<int>(r.start_redraws.size());
  }
  EXPECT_GT(redraws, 0) << "no start of 16 was against a wall: the test no longer tests that";
  EXPECT_EQ(Summarize(results).start_redraws, redraws);
}

TEST(WhereAmIBatchTest, ARunThatCannotBeRunIsCountedAndTheBatchGoesOn) {
  ToolOptions options;
  options.runs = 3;
  options.max_sim_s = 2.0;
  options.rings = {"wing1_corridor", "no_such_ring"};
  const std::vector<RunResult> results = RunSeeds(SmallMapSetup(), options);
  ASSERT_EQ(results.size(), 3u);
  EXPECT_FALSE(results[0].failed);
  EXPECT_TRUE(results[1].failed);
  EXPECT_EQ(results[1].ending(), Ending::kFailed);
  EXPECT_NE(results[1].ended.find("no_such_ring"), std::string::npos) << results[1].ended;
  EXPECT_FALSE(results[2].failed);
  const Summary s = Summarize(results);
  EXPECT_EQ(s.endings.at(Ending::kFailed), 1);
  EXPECT_EQ(s.endings.at(Ending::kNoneInTime), 2);  // 2 s is too short to localize
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
