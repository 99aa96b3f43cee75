#pragma once

#include <fmt/format.h>

#include <string>
#include <vector>

#include "common/quantile.h"

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
    return fmt::format("median {:.2f} ms, p99 {:.2f} ms over {}", Quantile(ms_, 0.5),
                       Quantile(ms_, 0.99), ms_.size());
  }

 private:
  std::vector<double> ms_;
};

}  // namespace stickrep::runtime
