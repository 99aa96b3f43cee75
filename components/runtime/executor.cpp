#include "runtime/executor.h"

#include <algorithm>

namespace stickrep::runtime {

void Executor::AddTimer(double period_s, std::function<void()> fn) {
  const auto period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(period_s));
  timers_.push_back(Timer{period, Clock::now() + period, std::move(fn)});
}

void Executor::Notify() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_ = true;
  }
  cv_.notify_one();
}

void Executor::SpinOnce(Clock::duration max_wait) {
  for (Drainable* d : drainables_) d->Drain();
  const auto now = Clock::now();
  auto next_due = now + max_wait;
  for (Timer& t : timers_) {
    if (t.next <= now) {
      t.fn();
      // Skip missed periods instead of firing a burst after a stall.
      t.next += t.period;
      if (t.next <= now) t.next = now + t.period;
    }
    next_due = std::min(next_due, t.next);
  }
  std::unique_lock<std::mutex> lock(mutex_);
  cv_.wait_until(lock, next_due, [this] { return pending_; });
  pending_ = false;
}

void Executor::Spin(const std::atomic<bool>& keep_running, Clock::time_point until) {
  while (keep_running.load() && Clock::now() < until) {
    SpinOnce(std::chrono::milliseconds(100));
  }
  for (Drainable* d : drainables_) d->Drain();
}

}  // namespace stickrep::runtime
