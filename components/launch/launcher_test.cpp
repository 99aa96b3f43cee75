#include "launch/launcher.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <csignal>
#include <fstream>
#include <sstream>
#include <thread>

#include "launch/child_process.h"

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

ProcessSpec Proc(const std::string& name, const std::string& executable,
                 const std::vector<std::string>& args) {
  ProcessSpec p;
  p.name = name;
  p.executable = executable;
  p.args = args;
  return p;
}

// No bin or config dir, no extra arguments; stopped 5 s after SIGTERM.
LaunchOptions Options() {
  LaunchOptions o;
  o.stop_grace_s = 5.0;
  return o;
}

// True when `pid` has ended: gone, or a zombie left for init to reap.
bool Ended(int pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(stat, line)) return true;
  const auto close = line.rfind(')');
  return close != std::string::npos && close + 2 < line.size() && line[close + 2] == 'Z';
}

TEST(ChildProcessTest, AChildEndsWhenItsParentIsKilled) {
  int fds[2];
  ASSERT_EQ(pipe(fds), 0);
  const pid_t parent = fork();
  ASSERT_GE(parent, 0);
  if (parent == 0) {  // a parent that starts a child, says its pid, and waits to be killed
    close(fds[0]);
    ChildProcess child("sleeper", {"sleep", "60"});
    const int pid = child.pid();
    if (write(fds[1], &pid, sizeof(pid)) != static_cast<ssize_t>(sizeof(pid))) _exit(1);
    for (;;) pause();
  }
  close(fds[1]);
  int child = 0;
  ASSERT_EQ(read(fds[0], &child, sizeof(child)), static_cast<ssize_t>(sizeof(child)));
  close(fds[0]);
  ASSERT_FALSE(Ended(child));
  ASSERT_EQ(kill(parent, SIGKILL), 0);
  waitpid(parent, nullptr, 0);
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!Ended(child) && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_TRUE(Ended(child)) << "the child of a killed parent is still running";
  if (!Ended(child)) kill(child, SIGKILL);
}

TEST(LauncherTest, RunEndsWhenTheNamedProcessExitsAndTheRestAreStopped) {
  std::ostringstream out;
  const auto results =
      RunGraph(Graph({Proc("quick", "sh", {"-c", "echo hello; echo 'x stopped: did it'"}),
                      Proc("slow", "sleep", {"20"})},
                     "quick"),
               Options(), out);
  ASSERT_EQ(results.size(), 2u);
  EXPECT_EQ(results[0].exit_code, 0);
  EXPECT_EQ(results[0].last_summary, "did it");
  EXPECT_EQ(results[1].signal, SIGTERM);
  EXPECT_THAT(out.str(), HasSubstr("quick | hello"));
  EXPECT_THAT(out.str(), HasSubstr("quick exited"));
}

TEST(LauncherTest, ExitCodesAreReported) {
  std::ostringstream out;
  const auto results = RunGraph(Graph({Proc("fails", "sh", {"-c", "exit 2"})}, ""),
                                Options(), out);
  EXPECT_EQ(results[0].exit_code, 2);
  EXPECT_THAT(out.str(), HasSubstr("every process exited"));
}

ProcessSpec WithRestart(ProcessSpec p, RestartPolicy::When when, int max_restarts) {
  p.restart.when = when;
  p.restart.backoff_initial_s = 0.05;
  p.restart.backoff_max_s = 0.4;
  p.restart.max_restarts = max_restarts;
  return p;
}

TEST(LauncherTest, AKilledProcessIsRestartedWithADoublingBackOffUpToTheLimit) {
  std::ostringstream out;
  const auto results = RunGraph(
      Graph({WithRestart(Proc("crashy", "sh", {"-c", "echo up; kill -9 $$"}),
                         RestartPolicy::When::kOnFailure, 3)},
            ""),
      Options(), out);
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].restarts, 3);
  EXPECT_EQ(results[0].failures, 4);
  EXPECT_EQ(results[0].signal, SIGKILL);
  EXPECT_THAT(out.str(), HasSubstr("crashy was killed by signal 9"));
  EXPECT_THAT(out.str(), HasSubstr("restarting it in 0.05 s (restart 1 of 3)"));
  EXPECT_THAT(out.str(), HasSubstr("restarting it in 0.10 s (restart 2 of 3)"));
  EXPECT_THAT(out.str(), HasSubstr("restarting it in 0.20 s (restart 3 of 3)"));
  EXPECT_THAT(out.str(), HasSubstr("it stays down (3 restarts were allowed)"));
  std::ostringstream table;
  PrintResults(results, table);
  EXPECT_THAT(table.str(), HasSubstr("RESTARTS"));
}

TEST(LauncherTest, OnFailureLeavesACleanExitDownAndAlwaysRestartsIt) {
  std::ostringstream out;
  const auto results = RunGraph(
      Graph({WithRestart(Proc("clean", "true", {}), RestartPolicy::When::kOnFailure, 5),
             WithRestart(Proc("again", "true", {}), RestartPolicy::When::kAlways, 2)},
            ""),
      Options(), out);
  EXPECT_EQ(results[0].restarts, 0);
  EXPECT_EQ(results[1].restarts, 2);
  EXPECT_EQ(results[1].failures, 0);
  EXPECT_THAT(out.str(), HasSubstr("clean exited with code 0"));
  EXPECT_THAT(out.str(), HasSubstr("restart policy on-failure"));
}

TEST(LauncherTest, BadInputIsNeverRestartedAndEndsTheRun) {
  std::ostringstream out;
  const auto results = RunGraph(
      Graph({WithRestart(Proc("bad", "sh", {"-c", "exit 2"}), RestartPolicy::When::kAlways, 0),
             Proc("slow", "sleep", {"20"})},
            ""),
      Options(), out);
  EXPECT_EQ(results[0].restarts, 0);
  EXPECT_EQ(results[0].exit_code, 2);
  EXPECT_THAT(out.str(), HasSubstr("bad refused its input"));
}

TEST(LauncherTest, ASecuredRunPassesTheDirectoryToEveryProcess) {
  std::ostringstream out;
  ProcessSpec server = Proc("server", "sh", {"-c", "echo server $0"});
  server.use_common_args = false;
  server.secure_args = {"{security_dir}/server.xml"};
  LaunchOptions options = Options();
  options.security_dir = "/keys";
  RunGraph(Graph({Proc("stickrep", "echo", {"args:"}), server}, ""), options, out);
  EXPECT_THAT(out.str(), HasSubstr("stickrep | args: --security-dir /keys"));
  EXPECT_THAT(out.str(), HasSubstr("server   | server /keys/server.xml"));
}


// Two secured processes that never authenticate each other: after the handshake timeout the
// later-started one is stopped and started again, whatever its restart policy; started again,
// it authenticates the other and the run ends.
TEST(LauncherTest, ASecuredPairThatNeverAuthenticatesHasItsLaterProcessRestarted) {
  std::ostringstream out;
  const std::string marker =
      ::testing::TempDir() + "/stickrep_heal_" + std::to_string(getpid());
  std::remove(marker.c_str());
  ProcessSpec early = Proc("early", "sh", {"-c",
      "echo \"secured: identity 'e' of /keys (participant stickrep-early)\"; exec sleep 20"});
  ProcessSpec late = Proc("late", "sh", {"-c",
      "echo \"secured: identity 'l' of /keys (participant stickrep-late)\"; "
      "if [ -e " + marker + " ]; then "
      "echo 'DDS Security: participant 01.0f (stickrep-early) authenticated'; exit 0; fi; "
      "touch " + marker + "; exec sleep 20"});
  early.use_common_args = late.use_common_args = false;
  LaunchGraph graph = Graph({early, late}, "late");
  graph.start_spacing_s = 0.1;
  graph.handshake_timeout_s = 1.0;
  LaunchOptions options = Options();
  options.security_dir = "/keys";
  const auto results = RunGraph(graph, options, out);
  std::remove(marker.c_str());
  EXPECT_THAT(out.str(), HasSubstr("launch: late and early have not authenticated each other"));
  ASSERT_EQ(results.size(), 2u);
  EXPECT_EQ(results[1].restarts, 1);
  EXPECT_EQ(results[1].exit_code, 0);
  EXPECT_THAT(out.str(), HasSubstr("ending the run: late exited"));
}

// Unsecured, nothing is watched.
TEST(LauncherTest, APlainRunIsNotWatchedForHandshakes) {
  std::ostringstream out;
  LaunchGraph graph = Graph({Proc("a", "sh", {"-c", "echo \"secured: identity 'a' of /k "
                                                     "(participant stickrep-a)\"; sleep 2"}),
                             Proc("b", "sh", {"-c", "echo \"secured: identity 'b' of /k "
                                                     "(participant stickrep-b)\"; sleep 2"})},
                            "b");
  graph.handshake_timeout_s = 0.5;
  RunGraph(graph, Options(), out);
  EXPECT_THAT(out.str(), ::testing::Not(HasSubstr("have not authenticated")));
}

}  // namespace
}  // namespace stickrep::launch
