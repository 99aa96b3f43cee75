#pragma once

#include <spdlog/logger.h>

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>

#include "common/strict_yaml.h"
#include "component/sample_counters.h"
#include "runtime/executor.h"
#include "runtime/participant.h"
#include "runtime/system_config.h"

namespace stickrep::runtime {

// What a process took in, sent and dropped (the component model's counters).
using SampleCounters = component::SampleCounters;

// What a process's node gets when it is configured: the DDS participant, the executor that
// runs its callbacks, its logger, the shared system settings and its own config section.
struct NodeContext {
  std::string name;
  Participant& participant;
  Executor& executor;
  std::shared_ptr<spdlog::logger> log;
  const SystemConfig& system;
  StrictYaml config;  // the component's own top-level key, e.g. `sonar:`
  SampleCounters& counters;
  std::function<int64_t()> now_ns;
  std::string host;  // the label of the host the process runs on (--host)
  // Ends the process cleanly after the current callback (a mission that is done).
  std::function<void()> request_stop;
};

// A process's logic behind an explicit lifecycle (nav2 lifecycle nodes): Configure creates
// endpoints and timers and may throw InputError (the process then exits 2 having cleaned
// up); callbacks run only between Activate and Deactivate.
class ProcessNode {
 public:
  virtual ~ProcessNode() = default;
  // Reads ctx.config (calling Finish on every mapping), creates writers, readers and timers.
  virtual void Configure(NodeContext& ctx) = 0;
  virtual void Activate() {}
  virtual void Deactivate() {}
  // One line printed at exit: what the process did, in figures.
  virtual std::string Summary() const { return ""; }
};

using NodeFactory = std::function<std::unique_ptr<ProcessNode>()>;

// The whole main() of a StickRep process: command line, config, logging, participant,
// lifecycle, SIGINT/SIGTERM. Returns the exit code: 0 on a clean stop, 2 on bad input,
// 1 on a runtime failure. `name` is the component name and its config's top-level key.
int RunProcess(int argc, char** argv, const std::string& name, const NodeFactory& make_node);

// Set by SIGINT/SIGTERM; RunProcess stops when it turns false.
std::atomic<bool>& KeepRunning();
void InstallSignalHandlers();

// Nanoseconds since the Unix epoch on the system clock.
int64_t WallClockNowNs();

}  // namespace stickrep::runtime
