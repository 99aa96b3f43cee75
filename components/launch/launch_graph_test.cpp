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
  EXPECT_EQ(SubstitutePlaceholders("--config={graph_dir}/a.yaml:{config_dir}",
                                   {{"graph_dir", "/d"}, {"config_dir", "/c"}}),
            "--config=/d/a.yaml:/c");
  EXPECT_THROW(SubstitutePlaceholders("{nope}", {{"graph_dir", "/d"}}), InputError);
}

const char* kParameterGraph =
    "launch:\n  name: x\n"
    "  parameters:\n    discovery_server: \"127.0.0.1:11811\"\n    host: robot\n"
    "  common_args: [--discovery-server, \"{discovery_server}\", --host, \"{host}\"]\n"
    "  processes:\n"
    "    - name: a\n      executable: stickrep-sonar\n"
    "    - name: server\n      executable: fast-discovery-server\n"
    "      args: [-p, \"{discovery_server}\"]\n      use_common_args: false\n";

TEST(LaunchGraphTest, ParametersHaveDefaultsThatSetOverrides) {
  const LaunchGraph g = LaunchGraph::Load(StrictYaml::LoadString(kParameterGraph, "d/g.yaml"));
  EXPECT_EQ(g.parameters.at("host"), "robot");
  EXPECT_TRUE(g.processes[0].use_common_args);
  EXPECT_FALSE(g.processes[1].use_common_args);
  const auto values = PlaceholderValues(g, "/c", {"discovery_server=10.1.0.1:11811"});
  EXPECT_EQ(SubstitutePlaceholders(g.common_args[1], values), "10.1.0.1:11811");
  EXPECT_EQ(SubstitutePlaceholders(g.common_args[3], values), "robot");
  EXPECT_EQ(values.at("graph_dir"), "d");
}

TEST(LaunchGraphTest, SetOfAnUnknownParameterOrWithoutValueIsRefused) {
  const LaunchGraph g = LaunchGraph::Load(StrictYaml::LoadString(kParameterGraph, "g.yaml"));
  try {
    PlaceholderValues(g, "/c", {"discovery_sever=10.1.0.1:11811"});
    FAIL() << "an unknown parameter was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("discovery_server, host"), std::string::npos) << e.what();
  }
  EXPECT_THROW(PlaceholderValues(g, "/c", {"host"}), InputError);
}

TEST(LaunchGraphTest, AnArgumentNamingAnUnknownPlaceholderIsRefusedAtLoad) {
  const char* text =
      "launch:\n  name: x\n  processes:\n"
      "    - name: a\n      executable: true\n      args: [\"{discovery_server}\"]\n";
  try {
    LaunchGraph::Load(StrictYaml::LoadString(text, "g.yaml"));
    FAIL() << "an unknown placeholder was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("g.yaml:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("{discovery_server}"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace stickrep::launch
