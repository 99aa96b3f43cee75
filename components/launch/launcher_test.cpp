#include "launch/launcher.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>

namespace stickrep::launch {
namespace {

using ::testing::HasSubstr;

LaunchGraph Graph(const std::vector<ProcessSpec>& processes, const std::string& until) {
  LaunchGraph g;
  g.file = "/tmp/graph.yaml";
  g.name = "test";
  g.processes = processes;
  g.until_exit_of = until;
  g.max_duration_s = 30.0;
  return g;
}

TEST(LauncherTest, RunEndsWhenTheNamedProcessExitsAndTheRestAreStopped) {
  std::ostringstream out;
  const auto results =
      RunGraph(Graph({{"quick", "sh", {"-c", "echo hello; echo 'x stopped: did it'"}},
                      {"slow", "sleep", {"20"}}},
                     "quick"),
               LaunchOptions{"", "", {}, 5.0, {}}, out);
  ASSERT_EQ(results.size(), 2u);
  EXPECT_EQ(results[0].exit_code, 0);
  EXPECT_EQ(results[0].last_summary, "did it");
  EXPECT_EQ(results[1].signal, SIGTERM);
  EXPECT_THAT(out.str(), HasSubstr("quick | hello"));
  EXPECT_THAT(out.str(), HasSubstr("quick exited"));
}

TEST(LauncherTest, ExitCodesAreReported) {
  std::ostringstream out;
  const auto results = RunGraph(Graph({{"fails", "sh", {"-c", "exit 2"}}}, ""),
                                LaunchOptions{"", "", {}, 5.0, {}}, out);
  EXPECT_EQ(results[0].exit_code, 2);
  EXPECT_THAT(out.str(), HasSubstr("every process exited"));
}

}  // namespace
}  // namespace stickrep::launch
