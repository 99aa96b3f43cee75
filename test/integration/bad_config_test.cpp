// Every process refuses bad configuration with exit code 2 and a message naming the file,
// the line and the key; every shipped configuration starts and stops cleanly.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "integration/process_fixture.h"

namespace stickrep::test {
namespace {

using ::testing::HasSubstr;

// Runs a process to completion (it is expected to stop by itself) and returns it.
std::unique_ptr<launch::ChildProcess> RunToEnd(const std::vector<std::string>& argv) {
  auto p = std::make_unique<launch::ChildProcess>(argv[0], argv);
  EXPECT_TRUE(p->WaitExit(60.0)) << argv[0] << " did not end";
  p->ReadLines(true);
  return p;
}

class BadConfigTest : public ::testing::Test {
 protected:
  std::unique_ptr<launch::ChildProcess> RunWithConfig(const std::string& exe,
                                                      const std::string& config_text) {
    const std::string path = WriteTempFile(exe + ".yaml", config_text);
    return RunToEnd({BinPath(exe), "--domain", "31", "--config", path, "--run-for", "5"});
  }
};

TEST_F(BadConfigTest, UnknownKeyExitsWithCode2NamingFileLineAndKey) {
  const auto p = RunWithConfig("stickrep-sonar", "sonar:\n  device: virtual\n  rate_hz: 3\n");
  EXPECT_EQ(p->exit_code(), 2);
  EXPECT_THAT(p->output(), HasSubstr("stickrep-sonar.yaml:3: key 'sonar.rate_hz': unknown key"));
}

TEST_F(BadConfigTest, MissingKeyExitsWithCode2) {
  const auto p = RunWithConfig("stickrep-camera", "camera:\n  other: 1\n");
  EXPECT_EQ(p->exit_code(), 2);
  EXPECT_THAT(p->output(), HasSubstr("key 'camera.device': missing required key"));
}

TEST_F(BadConfigTest, WrongValueTypeExitsWithCode2) {
  const auto p = RunWithConfig("stickrep-locomotion",
                               "locomotion:\n  device: virtual\n  control_rate_hz: fast\n"
                               "  command_timeout_s: 0.5\n  max_angular_rate_radps: 1\n");
  EXPECT_EQ(p->exit_code(), 2);
  EXPECT_THAT(p->output(), HasSubstr(":3: key 'locomotion.control_rate_hz': expected a number"));
}

TEST_F(BadConfigTest, OutOfRangeValueExitsWithCode2AndStatesTheRange) {
  const auto p = RunWithConfig("stickrep-locomotion",
                               "locomotion:\n  device: virtual\n  control_rate_hz: 20\n"
                               "  command_timeout_s: 0.5\n  max_angular_rate_radps: 50\n");
  EXPECT_EQ(p->exit_code(), 2);
  EXPECT_THAT(p->output(), HasSubstr(":5: key 'locomotion.max_angular_rate_radps': value 50"));
}

TEST_F(BadConfigTest, SetOverridesAConfigKeyAndIsCheckedLikeTheFile) {
  // A malformed --set, an unknown key set, and a replaying virtual robot without a recording
  // or with one that is not there: each exits 2 naming the key or the file.
  const auto malformed = RunToEnd({BinPath("stickrep-sonar"), "--domain", "31", "--set", "rate"});
  EXPECT_EQ(malformed->exit_code(), 2);
  EXPECT_THAT(malformed->output(), HasSubstr("expected KEY=VALUE"));
  const auto unknown =
      RunToEnd({BinPath("stickrep-sonar"), "--domain", "31", "--set", "rate_hz=3"});
  EXPECT_EQ(unknown->exit_code(), 2);
  EXPECT_THAT(unknown->output(), HasSubstr("key 'sonar.rate_hz': unknown key"));
  const auto no_file = RunToEnd(
      {BinPath("stickrep-virtual-robot"), "--domain", "31", "--set", "source=replay"});
  EXPECT_EQ(no_file->exit_code(), 2);
  EXPECT_THAT(no_file->output(), HasSubstr("name a recording"));
  const auto missing =
      RunToEnd({BinPath("stickrep-virtual-robot"), "--domain", "31", "--set", "source=replay",
                "--set", "replay.file=/nonexistent/run.db3"});
  EXPECT_EQ(missing->exit_code(), 2);
  EXPECT_THAT(missing->output(), HasSubstr("/nonexistent/run.db3: no such recording"));
}

TEST_F(BadConfigTest, QosProfileThatDoesNotExistExitsWithCode2) {
  std::string qos = "qos:\n  profiles:\n    sensor:\n      reliability: best_effort\n"
                    "      durability: volatile\n      history_depth: 5\n      deadline_s: 0\n"
                    "      liveliness_lease_s: 0\n      publish_mode: synchronous\n  streams:\n"
                    "    - topic: robot/sonar\n      profile: sensors\n"
                    "      reason: newest scan supersedes the rest\n";
  const std::string qos_path = WriteTempFile("qos.yaml", qos);
  const std::string system_path = WriteTempFile(
      "system.yaml", "system:\n  domain_id: 31\n  qos_file: " + qos_path + "\n  robot_file: " +
                         ConfigPath("robot.yaml") + "\n  map_file: " + std::string(STICKREP_SOURCE_DIR) +
                         "/maps/engineering_building_3f.yaml\n");
  const auto p = RunToEnd({BinPath("stickrep-sonar"), "--system", system_path, "--run-for", "5"});
  EXPECT_EQ(p->exit_code(), 2);
  EXPECT_THAT(p->output(), HasSubstr("qos.yaml:12: key 'qos.streams[0].profile': no QoS profile "
                                     "named 'sensors'"));
}

TEST_F(BadConfigTest, MalformedYamlExitsWithCode2) {
  const auto p = RunWithConfig("stickrep-executive", "executive:\n  required_components: [a, b\n");
  EXPECT_EQ(p->exit_code(), 2);
  EXPECT_THAT(p->output(), HasSubstr("malformed YAML"));
}

TEST_F(BadConfigTest, EveryShippedConfigStartsAndStopsCleanly) {
  for (const char* exe : {"stickrep-virtual-robot", "stickrep-sonar", "stickrep-camera",
                          "stickrep-locomotion", "stickrep-landmark", "stickrep-localizer",
                          "stickrep-executive"}) {
    const auto p = RunToEnd({BinPath(exe), "--domain", "32", "--run-for", "0.5"});
    EXPECT_EQ(p->exit_code(), 0) << exe << "\n" << p->output();
    EXPECT_THAT(p->output(), HasSubstr("stopped:")) << exe;
  }
}

// Fast DDS XML profiles and discovery servers (the two-host deployment).
std::unique_ptr<launch::ChildProcess> RunWithDeployment(const std::vector<std::string>& args) {
  std::vector<std::string> argv{BinPath("stickrep-sonar"), "--domain", "31"};
  argv.insert(argv.end(), args.begin(), args.end());
  if (std::find(argv.begin(), argv.end(), "--run-for") == argv.end()) {
    argv.insert(argv.end(), {"--run-for", "5"});
  }
  return RunToEnd(argv);
}

TEST(BadDeploymentTest, MissingProfileFileExitsWithCode2) {
  const auto p = RunWithDeployment({"--fastdds-profile", "/nonexistent/client.xml"});
  EXPECT_EQ(p->exit_code(), 2);
  EXPECT_THAT(p->output(), HasSubstr("/nonexistent/client.xml: no such Fast DDS XML profile file"));
}

TEST(BadDeploymentTest, MalformedProfileExitsWithCode2NamingTheLine) {
  const std::string path = WriteTempFile(
      "broken.xml", "<?xml version=\"1.0\"?>\n<dds>\n  <profiles>\n    <participant>\n</dds>\n");
  const auto p = RunWithDeployment({"--fastdds-profile", path});
  EXPECT_EQ(p->exit_code(), 2);
  EXPECT_THAT(p->output(), HasSubstr("broken.xml:4: malformed XML"));
}

TEST(BadDeploymentTest, UnknownProfileNameExitsWithCode2) {
  const auto p = RunWithDeployment(
      {"--fastdds-profile", std::string(STICKREP_SOURCE_DIR) + "/deploy/fastdds/discovery_client.xml",
       "--fastdds-profile-name", "stickrep_sever"});
  EXPECT_EQ(p->exit_code(), 2);
  EXPECT_THAT(p->output(), HasSubstr("key 'stickrep_sever': no participant profile with this name"));
}

TEST(BadDeploymentTest, MalformedServerAddressExitsWithCode2) {
  const auto p = RunWithDeployment({"--discovery-server", "base-station:eleven"});
  EXPECT_EQ(p->exit_code(), 2);
  EXPECT_THAT(p->output(), HasSubstr("not a list of IPv4 discovery server addresses IP:PORT"));
}

TEST(BadDeploymentTest, UnreachableServerTheProcessRunsAndWarnsPeriodically) {
  const auto p = RunWithDeployment({"--discovery-server", "10.255.255.1:11811", "--run-for", "7"});
  EXPECT_EQ(p->exit_code(), 0) << p->output();
  EXPECT_THAT(p->output(), HasSubstr("no discovery server reached at 10.255.255.1:11811 for 5 s"));
}

TEST(BadDeploymentTest, GraphWithABadProfileEndsTheRunWithCode2) {
  const std::string graph = WriteTempFile(
      "bad.launch.yaml",
      "launch:\n  name: bad profile\n  max_duration_s: 60\n"
      "  common_args: [--domain, \"31\", --fastdds-profile, /nonexistent/client.xml]\n"
      "  processes:\n    - name: sonar\n      executable: stickrep-sonar\n"
      "    - name: camera\n      executable: stickrep-camera\n");
  const auto p = RunToEnd({BinPath("stickrep-launch"), graph});
  EXPECT_EQ(p->exit_code(), 2) << p->output();
  EXPECT_THAT(p->output(), HasSubstr("refused its input (exit code 2)"));
}

// Every program, tool or process, refuses a bad command line with exit code 2 and CLI11's
// message, and prints its help with exit code 0 (common/tool_main.h).
const std::vector<std::string> kPrograms = {
    "stickrep-bag",      "stickrep-camera",   "stickrep-console",   "stickrep-executive",
    "stickrep-landmark", "stickrep-launch",   "stickrep-localizer", "stickrep-locomotion",
    "stickrep-map",      "stickrep-measure",  "stickrep-record",    "stickrep-replay",
    "stickrep-sensing",  "stickrep-sonar",    "stickrep-study",     "stickrep-transport-bench",
    "stickrep-virtual-robot", "stickrep-whereami"};

TEST(CommandLineTest, EveryProgramRefusesAnUnknownOptionWithCode2) {
  for (const std::string& program : kPrograms) {
    SCOPED_TRACE(program);
    const auto p = RunToEnd({BinPath(program), "--no-such-option"});
    EXPECT_EQ(p->exit_code(), 2) << p->output();
    // The first thing wrong: the unknown option, or a required argument missing before it.
    EXPECT_THAT(p->output(), HasSubstr("Run with --help for more information."));
  }
}

TEST(CommandLineTest, EveryProgramPrintsItsHelpWithCode0) {
  for (const std::string& program : kPrograms) {
    SCOPED_TRACE(program);
    const auto p = RunToEnd({BinPath(program), "--help"});
    EXPECT_EQ(p->exit_code(), 0) << p->output();
    EXPECT_THAT(p->output(), HasSubstr("Usage"));
  }
}

TEST(CommandLineTest, AMissingValueOrSubcommandIsCode2) {
  // CLI11's own codes for these were 114 (an option without its value) and 106 (extras).
  const auto no_value = RunToEnd({BinPath("stickrep-sensing"), "report", "--json"});
  EXPECT_EQ(no_value->exit_code(), 2) << no_value->output();
  const auto extra = RunToEnd({BinPath("stickrep-launch"), "a.yaml", "b.yaml"});
  EXPECT_EQ(extra->exit_code(), 2) << extra->output();
  const auto bad_number = RunToEnd({BinPath("stickrep-whereami"), "--runs", "many"});
  EXPECT_EQ(bad_number->exit_code(), 2) << bad_number->output();
}

}  // namespace
}  // namespace stickrep::test
