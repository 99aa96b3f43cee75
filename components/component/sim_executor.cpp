#include "component/sim_executor.h"

#include <algorithm>
#include <cmath>

namespace stickrep::component {

void SimExecutor::AddTimer(double period_s, std::function<void()> fire, double first_after_s) {
  if (!(period_s > 0.0)) throw std::invalid_argument("a timer's period must be positive");
  const auto ns = [](double s) { return static_cast<int64_t>(std::llround(s * 1e9)); };
  timers_.push_back({ns(period_s), now_ns_ + ns(first_after_s), std::move(fire)});
}

void SimExecutor::AddTimers(Component& component) {
  for (Timer& t : component.Timers()) AddTimer(t.period_s, std::move(t.fire));
}

void SimExecutor::Deliver() {
  while (!queue_.empty()) {
    const std::function<void()> deliver = std::move(queue_.front());
    queue_.pop_front();
    deliver();
    ++delivered_;
  }
}

void SimExecutor::Step() {
  Deliver();
  if (timers_.empty()) return;
  int64_t next = timers_.front().next_ns;
  for (const TimerEntry& t : timers_) next = std::min(next, t.next_ns);
  now_ns_ = next;
  // By index: a timer may add timers.
  for (size_t i = 0; i < timers_.size(); ++i) {
    if (timers_[i].next_ns != next) continue;
    timers_[i].next_ns += timers_[i].period_ns;
    std::function<void()> fire = timers_[i].fire;
    fire();
    Deliver();
  }
}

bool SimExecutor::RunUntil(const std::function<bool()>& done, double max_s) {
  const int64_t end_ns = start_ns_ + static_cast<int64_t>(std::llround(max_s * 1e9));
  while (now_ns_ < end_ns) {
    Step();
    if (done()) return true;
    if (timers_.empty()) return false;
  }
  return false;
}

}  // namespace stickrep::component
