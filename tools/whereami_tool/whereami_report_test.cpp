// The stickrep-whereami batch: seeds over worker threads, starts drawn again, runs that
// cannot be run, the observation model the map gets, and the tool's bad input.
#include "whereami_tool/whereami_report.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
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

// A copy of configs/ whose localizer.yaml gives the small map ("wing1_corridor") a model of
// its own naming `error_model_file`, in its on_maps block (one at the end if it has none).
std::string ConfigsWithOwnModel(const std::string& error_model_file) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(::testing::TempDir()) /
                       ("whereami_own_model_" + fs::path(error_model_file).stem().string());
  fs::remove_all(dir);
  fs::copy(fs::path(STICKREP_SOURCE_DIR) / "configs", dir, fs::copy_options::recursive);
  std::stringstream text;
  text << std::ifstream(dir / "localizer.yaml").rdbuf();
  std::string yaml = text.str();
  const std::string maps = "  on_maps:\n";
  std::size_t at = yaml.find(maps);
  if (at == std::string::npos) {
    at = yaml.size();
    yaml += maps;
  }
  yaml.insert(at + maps.size(), "    wing1_corridor:\n      error_model_file: " + error_model_file +
                                    "\n" +
                                    "      confidence_calibration_slope: 0.5\n"
                                    "      confidence_calibration_offset: -1.0\n"
                                    "      localized_confidence: 0.955\n"
                                    "      bayes_lost_threshold: 0.001\n"
                                    "      bayes_false_door_fit: false\n"
                                    "      bayes_max_missed_doors: 2\n");
  std::ofstream(dir / "localizer.yaml") << yaml;
  return dir.string();
}

TEST(WhereAmIToolTest, TheMapsOwnModelIsNamedAndItsFilesCheckedBeforeAnyRun) {
  ToolOptions o;
  o.map_file = kSmallMap;
  o.runs = 1;
  o.threads = 1;
  o.max_sim_s = 1.0;
  o.config_dir = ConfigsWithOwnModel("error_model_live.yaml");
  std::ostringstream out, err;
  ASSERT_EQ(RunTool(o, out, err), 0) << err.str();
  const std::string header = out.str().substr(0, out.str().find('\n'));
  EXPECT_NE(header.find("the map's own, measured on it: error_model_live.yaml, declared at "
                        "confidence 0.955"),
            std::string::npos)
      << header;

  // A file the floor's block names that is not there is bad input, before any run.
  o.config_dir = ConfigsWithOwnModel("no_such_model.yaml");
  std::ostringstream out2, err2;
  EXPECT_EQ(RunTool(o, out2, err2), kExitBadInput);
  EXPECT_NE(err2.str().find("no_such_model.yaml"), std::string::npos) << err2.str();
  EXPECT_EQ(out2.str().find("seed"), std::string::npos) << out2.str();
}

}  // namespace
}  // namespace stickrep::whereami
