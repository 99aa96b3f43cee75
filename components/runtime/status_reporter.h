#pragma once

#include <memory>
#include <string>

#include "runtime/participant.h"
#include "runtime/process.h"

namespace stickrep::runtime {

// How often a running process publishes its status (the heartbeat). The system/status
// liveliness lease (configs/qos.yaml) is twice this.
inline constexpr double kHeartbeatPeriodS = 0.5;

// Publishes this process's lifecycle state and counters on system/status (keyed by the
// process name). The topic's liveliness lease lets any reader notice a process that died.
class StatusReporter {
 public:
  enum class State { kUnconfigured, kInactive, kActive, kFinalized };

  StatusReporter(Participant& participant, std::string component, std::string host,
                 const SampleCounters& counters);
  ~StatusReporter();
  void Publish(State state, const std::string& message);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace stickrep::runtime
