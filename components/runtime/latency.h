#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <vector>

namespace stickrep::runtime {

// Latencies a process measures over its run (wall clock), summarised as median and 99th
// percentile for its exit summary.
class LatencyLog {
 public:
  void Add(double ms) { ms_.push_back(ms); }
  std::size_t size() const { return ms_.size(); }
  // "median 1.8 ms, p99 6.8 ms over 45", or "none" before the first.
  std::string Summary() const {
    if (ms_.empty()) return "none";
    std::vector<double> v = ms_;
    std::sort(v.begin(), v.end());
    const auto at = [&](double q) { return v[static_cast<std::size_t>(q * (v.size() - 1) + 0.5)]; };
    return fmt::format("median {:.2f} ms, p99 {:.2f} ms over {}", at(0.5), at(0.99), v.size());
  }

 private:
  std::vector<double> ms_;
};

}  // namespace stickrep::runtime
