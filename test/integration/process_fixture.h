#pragma once

#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "launch/child_process.h"
#include "runtime/discovery.h"
#include "runtime/endpoint.h"
#include "runtime/participant.h"

namespace stickrep::test {

// Holds an exclusive lock named after a DDS domain for as long as it lives. ctest -j runs the
// tests of one file side by side and they share the file's domain: the lock keeps one
// test's processes from hearing another's samples.
class DomainLock {
 public:
  explicit DomainLock(int domain_id);
  ~DomainLock();
  DomainLock(const DomainLock&) = delete;
  DomainLock& operator=(const DomainLock&) = delete;

 private:
  int fd_ = -1;
};

// Starts StickRep processes from build/bin on one DDS domain (held with a DomainLock) and
// joins that domain with a participant of its own, so a test can publish, listen, and wait
// for discovery and data with a bounded timeout instead of sleeping.
class ProcessFixture : public ::testing::Test {
 protected:
  explicit ProcessFixture(int domain_id);
  ~ProcessFixture() override;

  // Starts build/bin/<executable> with --domain and `args`.
  launch::ChildProcess& Start(const std::string& executable,
                              const std::vector<std::string>& args = {});
  // Spins the test's executor until `done` holds or the timeout passes.
  bool SpinUntil(const std::function<bool()>& done, double timeout_s);
  // SIGTERM to every process still running; each must exit with code 0 in the timeout.
  void StopAllAndExpectCleanExit(double timeout_s = 15.0);
  // The output of every process so far, for failure messages.
  std::string Outputs();

  runtime::Participant& participant() { return *participant_; }
  // Every endpoint the test's participant has discovered on the domain.
  std::vector<runtime::TopicSummary> Topics() const {
    return runtime::Summarise(participant_->discovery().Endpoints());
  }
  runtime::Executor& executor() { return executor_; }
  int domain_id() const { return domain_id_; }

 private:
  int domain_id_;
  DomainLock lock_;
  runtime::Executor executor_;
  std::unique_ptr<runtime::Participant> participant_;
  std::vector<std::unique_ptr<launch::ChildProcess>> processes_;
};

// build/bin/<name>
std::string BinPath(const std::string& name);
// configs/<name>
std::string ConfigPath(const std::string& name);
// A file of the source tree, by its path relative to the top.
std::string SourcePath(const std::string& rel);
// Seconds since the epoch on the wall clock: comparable with the simulated time the
// virtual robot stamps at real-time factor 1.
double WallNowS();
// Runs a shell command (stderr joined to stdout): its exit code (-1 if it did not exit) and
// its output.
std::pair<int, std::string> Shell(const std::string& command);
// Writes `text` to a fresh file under the test's temporary directory; returns its path.
std::string WriteTempFile(const std::string& name, const std::string& text);
// A shipped config file (configs/<file>) with some keys of its section replaced.
std::string ConfigWith(const std::string& file, const std::map<std::string, std::string>& keys);
// The small map of the Where-am-I tests: one corridor of the Engineering Building.
constexpr const char* kSmallMap = STICKREP_SOURCE_DIR "/test/maps/wing1_corridor.yaml";
constexpr int kSmallMapEdges = 118;
// The shipped system.yaml on the small map (paths made absolute: it is written elsewhere),
// as a temporary file named `name`.
std::string SmallMapSystem(const std::string& name);

}  // namespace stickrep::test
