#include "common/worker_pool.h"

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace stickrep {
namespace {

TEST(WorkerPoolTest, EveryIndexRunsOnceWithItsResultInItsSlot) {
  std::vector<int> square(1000, -1);
  std::atomic<int> runs{0};
  ParallelFor(square.size(), 3, [&] {
    return [&](std::size_t i) {
      square[i] = static_cast<int>(i * i);
      ++runs;
    };
  });
  EXPECT_EQ(runs.load(), 1000);
  for (std::size_t i = 0; i < square.size(); ++i) EXPECT_EQ(square[i], static_cast<int>(i * i));
}

TEST(WorkerPoolTest, EachThreadMakesItsOwnTaskAndNeverMoreThreadsThanIndices) {
  std::atomic<int> made{0};
  ParallelFor(2, 8, [&] {
    ++made;
    return [](std::size_t) {};
  });
  EXPECT_LE(made.load(), 2);
  EXPECT_GE(made.load(), 1);
  made = 0;
  ParallelFor(5, 0, [&] {  // 0 threads: one
    ++made;
    return [](std::size_t) {};
  });
  EXPECT_EQ(made.load(), 1);
}

TEST(WorkerPoolTest, AnExceptionStopsTheBatchAndReachesTheCaller) {
  // One thread: nothing after the failing index is handed out.
  std::atomic<std::size_t> ran{0};
  const auto fail_at_10 = [&] {
    return [&](std::size_t i) {
      ++ran;
      if (i == 10) throw std::runtime_error("index 10");
    };
  };
  EXPECT_THROW(ParallelFor(100000, 1, fail_at_10), std::runtime_error);
  EXPECT_EQ(ran.load(), 11u);
  // Two threads: the other thread stops at its next index. Once index 10 has thrown, each
  // later index takes 0.2 ms, so the other thread would need 20 s to drain the batch while
  // the failing thread goes from its throw to the pool's record of it; with trivial tasks
  // it could drain it in that gap on a loaded machine.
  ran = 0;
  std::atomic<bool> thrown{false};
  EXPECT_THROW(ParallelFor(100000, 2,
                           [&] {
                             return [&](std::size_t i) {
                               ++ran;
                               if (i == 10) {
                                 thrown = true;
                                 throw std::runtime_error("index 10");
                               }
                               if (i > 10 && thrown) {
                                 std::this_thread::sleep_for(std::chrono::microseconds(200));
                               }
                             };
                           }),
               std::runtime_error);
  EXPECT_LT(ran.load(), 100000u);
  // A task that cannot be made fails the same way.
  EXPECT_THROW(ParallelFor(3, 2, []() -> IndexTask { throw std::invalid_argument("setup"); }),
               std::invalid_argument);
}

TEST(WorkerPoolTest, ProgressEndsAtTheCount) {
  std::size_t last_done = 0, last_count = 0;
  ParallelFor(
      50, 2,
      [] { return [](std::size_t) { std::this_thread::sleep_for(std::chrono::milliseconds(2)); }; },
      [&](std::size_t done, std::size_t count) {
        EXPECT_LE(done, count);
        last_done = done;
        last_count = count;
      });
  EXPECT_EQ(last_done, 50u);
  EXPECT_EQ(last_count, 50u);
}

}  // namespace
}  // namespace stickrep
