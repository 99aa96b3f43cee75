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

TEST(LaunchGraphTest, RestartPolicyOfTheGraphIsEveryProcesssUnlessItNamesItsOwn) {
  const char* text =
      "launch:\n  name: x\n"
      "  restart: {policy: on-failure, backoff_initial_s: 0.25, backoff_max_s: 4, "
      "max_restarts: 3}\n"
      "  processes:\n"
      "    - name: a\n      executable: true\n"
      "    - name: b\n      executable: true\n      restart: never\n"
      "    - name: c\n      executable: true\n      restart: {policy: always}\n";
  const LaunchGraph g = LaunchGraph::Load(StrictYaml::LoadString(text, "g.yaml"));
  EXPECT_EQ(g.processes[0].restart.when, RestartPolicy::When::kOnFailure);
  EXPECT_DOUBLE_EQ(g.processes[0].restart.backoff_initial_s, 0.25);
  EXPECT_DOUBLE_EQ(g.processes[0].restart.backoff_max_s, 4.0);
  EXPECT_EQ(g.processes[0].restart.max_restarts, 3);
  EXPECT_EQ(g.processes[1].restart.when, RestartPolicy::When::kNever);
  EXPECT_EQ(g.processes[2].restart.when, RestartPolicy::When::kAlways);
  EXPECT_EQ(g.processes[2].restart.max_restarts, 3);  // the rest from the graph's
}

TEST(LaunchGraphTest, WithoutARestartPolicyNothingIsRestarted) {
  const char* text = "launch:\n  name: x\n  processes:\n    - name: a\n      executable: true\n";
  const LaunchGraph g = LaunchGraph::Load(StrictYaml::LoadString(text, "g.yaml"));
  EXPECT_EQ(g.processes[0].restart.when, RestartPolicy::When::kNever);
}

// A bad restart entry is refused with the file, the line and the key.
void ExpectRefused(const std::string& restart, const std::string& key, int line) {
  const std::string text = "launch:\n  name: x\n  processes:\n    - name: a\n"
                           "      executable: true\n      restart:" + restart + "\n";
  try {
    LaunchGraph::Load(StrictYaml::LoadString(text, "g.yaml"));
    FAIL() << "taken: " << restart;
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("g.yaml:" + std::to_string(line)), std::string::npos) << what;
    EXPECT_NE(what.find(key), std::string::npos) << what;
  }
}

TEST(LaunchGraphTest, BadRestartPoliciesAreRefusedWithFileLineAndKey) {
  ExpectRefused(" sometimes", "restart", 6);
  ExpectRefused(" {policy: on-failure, backoff_initial_s: 0}", "backoff_initial_s", 6);
  ExpectRefused(" {policy: always, backoff_initial_s: 2, backoff_max_s: 1}", "backoff_max_s", 6);
  ExpectRefused(" {policy: always, max_restarts: -1}", "max_restarts", 6);
  ExpectRefused("\n        policy: always\n        backof_max_s: 3", "backof_max_s", 8);
  ExpectRefused(" {backoff_max_s: 3}", "policy", 6);
}

TEST(LaunchGraphTest, SecureArgsMayNameTheSecurityDirectory) {
  const char* text =
      "launch:\n  name: x\n  processes:\n"
      "    - name: server\n      executable: fast-discovery-server\n"
      "      use_common_args: false\n"
      "      secure_args: [-x, \"{security_dir}/discovery_server.xml\"]\n";
  const LaunchGraph g = LaunchGraph::Load(StrictYaml::LoadString(text, "g.yaml"));
  const auto values = PlaceholderValues(g, "/c", {}, "/keys");
  EXPECT_EQ(SubstitutePlaceholders(g.processes[0].secure_args[1], values),
            "/keys/discovery_server.xml");
}

}  // namespace
}  // namespace stickrep::launch
