#pragma once

#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "runtime/bench/bench_link.h"

namespace stickrep::runtime::bench {

// What one (implementation, QoS profile, payload size) case measured.
struct CaseResult {
  Impl impl = Impl::kRuntime;
  std::string profile;
  std::size_t bytes = 0;
  // Latency phase: pings sent one at a time, each after the previous pong.
  int samples = 0;
  int lost = 0;                     // no pong within the per-sample timeout
  std::vector<double> one_way_us;   // round trip / 2 of every ping that came back
  double p50_us = 0.0;              // set by Summarise()
  double p99_us = 0.0;
  // Throughput phase: pings written back to back for a fixed time, pongs counted.
  uint64_t tput_sent = 0;
  uint64_t tput_received = 0;
  double tput_seconds = 0.0;  // first write to last pong
  // Adds the samples and counts of another round of the same case.
  void Merge(const CaseResult& other);
  // Sets p50_us and p99_us from one_way_us.
  void Summarise();
  double PongsPerSecond() const;
  double PayloadMegabytesPerSecond() const;  // payload bytes of the pongs, 1 MB = 1e6 B
};

// How the run was set up, printed above the table and put into the JSON.
struct RunInfo {
  int domain_id = 0;
  int rounds = 1;
  std::string qos_file;
  std::string fastdds_profile;  // empty: UDPv4 only, as every process by default
  std::string echo_prefix;
  int samples = 0;
  int large_samples = 0;
  double throughput_s = 0.0;
  double sample_timeout_s = 0.0;
};


// (runtime p50 - raw p50) / raw p50 in % for the case's profile and size, if both ran.
std::optional<double> MedianOverheadPercent(const std::vector<CaseResult>& results,
                                            const std::string& profile, std::size_t bytes);

void PrintTable(std::ostream& out, const RunInfo& info, const std::vector<CaseResult>& results);
nlohmann::json ToJson(const RunInfo& info, const std::vector<CaseResult>& results);

}  // namespace stickrep::runtime::bench
