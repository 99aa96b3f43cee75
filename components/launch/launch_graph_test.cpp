#include "launch/launch_graph.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace stickrep::launch {
namespace {

TEST(LaunchGraphTest, ShippedGraphsLoad) {
  const std::filesystem::path deploy = std::string(STICKREP_SOURCE_DIR) + "/deploy";
  int loaded = 0;
  for (const auto& entry : std::filesystem::directory_iterator(deploy)) {
    if (entry.path().extension() == ".yaml" &&
        entry.path().filename().string().find(".launch.") != std::string::npos) {
      const LaunchGraph g = LaunchGraph::LoadFile(entry.path().string());
      EXPECT_FALSE(g.processes.empty()) << entry.path();
      loaded++;
    }
  }
  EXPECT_GE(loaded, 1);
}

TEST(LaunchGraphTest, UntilExitOfMustNameAProcess) {
  const char* text =
      "launch:\n  name: x\n  until_exit_of: nobody\n  processes:\n"
      "    - name: a\n      executable: true\n";
  EXPECT_THROW(LaunchGraph::Load(StrictYaml::LoadString(text, "g.yaml")), InputError);
}

TEST(LaunchGraphTest, DuplicateProcessNamesAreRejected) {
  const char* text =
      "launch:\n  name: x\n  processes:\n"
      "    - name: a\n      executable: true\n    - name: a\n      executable: true\n";
  EXPECT_THROW(LaunchGraph::Load(StrictYaml::LoadString(text, "g.yaml")), InputError);
}

TEST(LaunchGraphTest, PlaceholdersAreSubstituted) {
  EXPECT_EQ(SubstitutePlaceholders("--config={graph_dir}/a.yaml:{config_dir}", "/d", "/c"),
            "--config=/d/a.yaml:/c");
}

}  // namespace
}  // namespace stickrep::launch
