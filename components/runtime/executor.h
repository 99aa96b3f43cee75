#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <vector>

namespace stickrep::runtime {

// Something that has samples or events waiting to be handled on the executor's thread.
class Drainable {
 public:
  virtual ~Drainable() = default;
  // Hands every waiting sample or event to its callback; runs on the executor thread only.
  virtual void Drain() = 0;
};

// Runs a process's logic on one thread: DDS listener threads only queue and Notify(); the
// executor drains readers and fires periodic timers, so component logic never needs locks.
class Executor {
 public:
  using Clock = std::chrono::steady_clock;

  void Add(Drainable* d) { drainables_.push_back(d); }
  // Forgets a drainable (its destructor calls this): a reader destroyed while the executor
  // lives on is never drained again. Called on the thread that spins, like Add.
  void Remove(Drainable* d) {
    drainables_.erase(std::remove(drainables_.begin(), drainables_.end(), d), drainables_.end());
  }
  // Calls `fn` every `period_s`, first after one period.
  void AddTimer(double period_s, std::function<void()> fn);
  // Wakes the executor (thread safe, callable from any thread).
  void Notify();
  // Runs until Stop() or `until`; returns when stopped.
  void Spin(const std::atomic<bool>& keep_running, Clock::time_point until);
  // One round: drain everything, fire due timers, then wait for at most `max_wait`.
  void SpinOnce(Clock::duration max_wait);

 private:
  struct Timer {
    Clock::duration period;
    Clock::time_point next;
    std::function<void()> fn;
  };
  std::vector<Drainable*> drainables_;
  std::vector<Timer> timers_;
  std::mutex mutex_;
  std::condition_variable cv_;
  bool pending_ = false;
};

}  // namespace stickrep::runtime
