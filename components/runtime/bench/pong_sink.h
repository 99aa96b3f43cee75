#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <utility>

#include "sensors.h"

namespace stickrep::runtime::bench {

// Where the driver's pongs land (on the link's reception thread) and where the sending
// thread waits for them. A pong is known by the ping id the echo copied back (width_px).
class PongSink {
 public:
  using Clock = std::chrono::steady_clock;

  // Called for every pong; records its arrival time.
  void OnPong(const msgs::Image& pong) {
    const Clock::time_point now = Clock::now();
    const uint32_t id = pong.width_px();
    std::lock_guard<std::mutex> lock(mutex_);
    if (counting_ && id >= count_from_) {
      counted_++;
      last_counted_ = now;
    }
    if (id == expected_) {
      arrived_ = now;
      cv_.notify_all();
    }
  }

  // Latency: the next pong to wait for (call before sending the ping).
  void Expect(uint32_t id) {
    std::lock_guard<std::mutex> lock(mutex_);
    expected_ = id;
    arrived_.reset();
  }
  // The arrival time of the expected pong, or nullopt after `timeout_s`.
  std::optional<Clock::time_point> Wait(double timeout_s) {
    std::unique_lock<std::mutex> lock(mutex_);
    cv_.wait_for(lock, std::chrono::duration<double>(timeout_s),
                 [this] { return arrived_.has_value(); });
    return arrived_;
  }

  // Throughput: counts pongs with ids from `first_id` on, from zero.
  void CountFrom(uint32_t first_id) {
    std::lock_guard<std::mutex> lock(mutex_);
    counting_ = true;
    count_from_ = first_id;
    counted_ = 0;
  }
  // Waits until `n` pongs were counted or none came for `quiet_s`, stops counting, and
  // returns the count and the time of the last counted pong.
  std::pair<uint64_t, Clock::time_point> FinishCounting(uint64_t n, double quiet_s) {
    std::unique_lock<std::mutex> lock(mutex_);
    for (uint64_t before = counted_ + 1; counted_ < n && counted_ != before;) {
      before = counted_;
      cv_.wait_for(lock, std::chrono::duration<double>(quiet_s));
    }
    counting_ = false;
    return {counted_, last_counted_};
  }

 private:
  std::mutex mutex_;
  std::condition_variable cv_;
  uint32_t expected_ = 0;  // ids start at 1
  std::optional<Clock::time_point> arrived_;
  bool counting_ = false;
  uint32_t count_from_ = 0;
  uint64_t counted_ = 0;
  Clock::time_point last_counted_{};
};

}  // namespace stickrep::runtime::bench
