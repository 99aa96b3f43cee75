#include "runtime/executor.h"

#include <gtest/gtest.h>

#include <thread>

namespace stickrep::runtime {
namespace {

class CountingDrainable : public Drainable {
 public:
  void Drain() override { drains++; }
  int drains = 0;
};

TEST(ExecutorTest, TimerFiresRepeatedly) {
  Executor ex;
  int fired = 0;
  ex.AddTimer(0.01, [&] { fired++; });
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (fired < 3 && std::chrono::steady_clock::now() < until) {
    ex.SpinOnce(std::chrono::milliseconds(50));
  }
  EXPECT_GE(fired, 3);
}

TEST(ExecutorTest, NotifyFromAnotherThreadWakesTheWait) {
  Executor ex;
  CountingDrainable d;
  ex.Add(&d);
  std::thread t([&] { ex.Notify(); });
  t.join();
  // A pending notification must end the wait at once rather than after an hour.
  ex.SpinOnce(std::chrono::hours(1));
  EXPECT_EQ(d.drains, 1);
}

TEST(ExecutorTest, SpinStopsWhenAskedAndDrainsOnceMore) {
  Executor ex;
  CountingDrainable d;
  ex.Add(&d);
  std::atomic<bool> keep_running{false};
  ex.Spin(keep_running, Executor::Clock::time_point::max());
  EXPECT_EQ(d.drains, 1);
}

TEST(ExecutorTest, ARemovedDrainableIsNeverDrainedAgain) {
  Executor ex;
  CountingDrainable kept, removed;
  ex.Add(&kept);
  ex.Add(&removed);
  ex.Notify();
  ex.SpinOnce(std::chrono::milliseconds(0));
  ex.Remove(&removed);
  ex.Notify();
  ex.SpinOnce(std::chrono::milliseconds(0));
  EXPECT_EQ(kept.drains, 2);
  EXPECT_EQ(removed.drains, 1);
}

}  // namespace
}  // namespace stickrep::runtime
