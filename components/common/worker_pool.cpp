#include "common/worker_pool.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace stickrep {

void ParallelFor(std::size_t count, int threads, const std::function<IndexTask()>& make_task,
                 const std::function<void(std::size_t, std::size_t)>& progress) {
  if (count == 0) {
    if (progress) progress(0, 0);
    return;
  }
  const std::size_t workers = std::clamp<std::size_t>(threads > 0 ? threads : 1, 1, count);
  std::atomic<std::size_t> next{0}, done{0};
  std::atomic<bool> failed{false};
  std::exception_ptr first_error;
  std::mutex error_mutex;
  const auto work = [&] {
    try {
      const IndexTask task = make_task();
      for (std::size_t i = next++; i < count && !failed; i = next++) {
        task(i);
        ++done;
      }
    } catch (...) {
      const std::lock_guard<std::mutex> lock(error_mutex);
      if (!first_error) first_error = std::current_exception();
      failed = true;
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(workers);
  for (std::size_t t = 0; t < workers; ++t) pool.emplace_back(work);
  if (progress) {
    while (done < count && !failed) {
      progress(done, count);
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  }
  for (std::thread& t : pool) t.join();
  if (first_error) std::rethrow_exception(first_error);
  if (progress) progress(count, count);
}

}  // namespace stickrep
