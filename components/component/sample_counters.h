#pragma once

#include <spdlog/logger.h>

#include <cstdint>
#include <map>
#include <memory>
#include <string>

namespace stickrep::component {

// Counts what a component takes in, sends out and drops, and warns about drops without
// flooding the log: the first few of each reason, then every 100th.
class SampleCounters {
 public:
  explicit SampleCounters(std::shared_ptr<spdlog::logger> log) : log_(std::move(log)) {}
  void CountIn() { in_++; }
  void CountOut() { out_++; }
  // A bad sample was dropped: counted per reason and warned about.
  void Drop(const std::string& topic, const std::string& reason);
  uint64_t in() const { return in_; }
  uint64_t out() const { return out_; }
  uint64_t dropped() const { return dropped_; }
  const std::map<std::string, uint64_t>& dropped_by_reason() const { return by_reason_; }
  // The last drop, as warned ("dropped a sample on T: reason"); empty before the first.
  const std::string& last_warning() const { return last_warning_; }

 private:
  std::shared_ptr<spdlog::logger> log_;
  uint64_t in_ = 0;
  uint64_t out_ = 0;
  uint64_t dropped_ = 0;
  std::map<std::string, uint64_t> by_reason_;
  std::string last_warning_;
};

}  // namespace stickrep::component
