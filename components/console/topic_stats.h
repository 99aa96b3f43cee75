#pragma once

// What `stickrep-console hz` and `delay` compute from the samples of one topic: the rate and
// the spread of the period between receptions, and the delay from the writer's source
// timestamp to reception, over a sliding window. No DDS: the console feeds it.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

namespace stickrep::console {

struct Spread {
  std::size_t n = 0;
  double mean = 0.0, min = 0.0, max = 0.0, stddev = 0.0;
};
Spread SpreadOf(const std::vector<double>& values);

class TopicWindow {
 public:
  explicit TopicWindow(std::size_t window) : window_(window < 2 ? 2 : window) {}
  void Add(std::int64_t source_ns, std::int64_t reception_ns, std::size_t bytes);
  std::uint64_t total() const { return total_; }
  // Periods between consecutive receptions in the window, seconds.
  Spread Period() const;
  // Reception minus source timestamp of each sample in the window, ms.
  Spread DelayMs() const;
  double MeanBytes() const;

 private:
  struct Sample {
    std::int64_t source_ns, reception_ns;
    std::size_t bytes;
  };
  std::size_t window_;
  std::deque<Sample> samples_;
  std::uint64_t total_ = 0;
};

// The known names closest to `name` (edit distance at most a third of its length, at least
// 3), closest first: "did you mean" for a mistyped topic.
std::vector<std::string> CloseNames(const std::string& name, const std::vector<std::string>& known);

}  // namespace stickrep::console
