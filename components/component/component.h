#pragma once

#include <spdlog/logger.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "component/sample_counters.h"

namespace stickrep::component {

// Where a component reads the time: the wall clock in a deployed process, the simulated
// clock in the in-process executor. Nanoseconds; 0 is never a valid time.
class Clock {
 public:
  virtual ~Clock() = default;
  virtual int64_t NowNs() const = 0;
};

// Where a component sends samples of one topic. The transport numbers them (header.sequence);
// the component stamps them (header.stamp_ns). False when the transport refused the sample.
template <typename T>
class Publisher {
 public:
  virtual ~Publisher() = default;
  virtual bool Publish(const T& sample) = 0;
};

// What every component is given: the clock, its logger, the counters of what it took in,
// sent and dropped, and a way to end the run (a mission that is done).
struct Context {
  std::string name;
  const Clock& clock;
  std::shared_ptr<spdlog::logger> log;
  SampleCounters& counters;
  std::function<void()> request_stop = [] {};
  int64_t NowNs() const { return clock.NowNs(); }
};

// Work a component wants done periodically, on the executor's clock.
struct Timer {
  double period_s;
  std::function<void()> fire;
};

// A process's logic: typed inputs (its On... methods, called by the transport's adapter or
// the in-process executor), outputs through injected publishers, time from the injected
// clock. No middleware type appears in a component.
class Component {
 public:
  virtual ~Component() = default;
  // Periodic work; asked once, after construction.
  virtual std::vector<Timer> Timers() { return {}; }
  virtual void Activate() {}
  virtual void Deactivate() {}
  // One line printed at exit: what the component did, in figures.
  virtual std::string Summary() const { return ""; }
};

}  // namespace stickrep::component
