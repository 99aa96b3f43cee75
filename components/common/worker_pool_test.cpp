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
  std::atomic<std::size_t> ran{0};
  EXPECT_THROW(ParallelFor(100000, 2,
                           [&] {
                             return [&](std::size_t i) {
                               ++ran;
                               if (i == 10) throw std::runtime_error("index 10");
                             };
                           }),
               std::runtime_error);
  EXPECT_LT(ran.load(), 100000u);  // no further indices were handed out once it failed
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
