#include "runtime/bench/bench_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <set>
#include <utility>

#include "common/quantile.h"

namespace stickrep::runtime::bench {

void CaseResult::Merge(const CaseResult& other) {
  samples += other.samples;
  lost += other.lost;
  one_way_us.insert(one_way_us.end(), other.one_way_us.begin(), other.one_way_us.end());
  tput_sent += other.tput_sent;
  tput_received += other.tput_received;
  tput_seconds += other.tput_seconds;
}

void CaseResult::Summarise() {
  p50_us = Quantile(one_way_us, 0.50);
  p99_us = Quantile(one_way_us, 0.99);
}

double CaseResult::PongsPerSecond() const {
  return tput_seconds > 0.0 ? static_cast<double>(tput_received) / tput_seconds : 0.0;
}

double CaseResult::PayloadMegabytesPerSecond() const {
  return PongsPerSecond() * static_cast<double>(bytes) / 1e6;
}

std::optional<double> MedianOverheadPercent(const std::vector<CaseResult>& results,
                                            const std::string& profile, std::size_t bytes) {
  const CaseResult* runtime = nullptr;
  const CaseResult* raw = nullptr;
  for (const CaseResult& r : results) {
    if (r.profile != profile || r.bytes != bytes || r.samples == r.lost) continue;
    (r.impl == Impl::kRuntime ? runtime : raw) = &r;
  }
  if (runtime == nullptr || raw == nullptr || raw->p50_us <= 0.0) return std::nullopt;
  return (runtime->p50_us - raw->p50_us) / raw->p50_us * 100.0;
}

namespace {

// The (profile, size) pairs in the order they first appear.
std::vector<std::pair<std::string, std::size_t>> Cases(const std::vector<CaseResult>& results) {
  std::vector<std::pair<std::string, std::size_t>> cases;
  std::set<std::pair<std::string, std::size_t>> seen;
  for (const CaseResult& r : results) {
    if (seen.insert({r.profile, r.bytes}).second) cases.emplace_back(r.profile, r.bytes);
  }
  return cases;
}

void PrintHeader(std::ostream& out, const RunInfo& info) {
  out << fmt::format(
      "transport bench: domain {}, QoS profiles from {}, {}{}\n"
      "{} round(s), each with a fresh echo per implementation and profile; per round:\n"
      "latency: {} pings one at a time ({} above 64 kB), one-way = round trip / 2, "
      "no pong within {:g} s = lost\n"
      "throughput: pings written back to back for {:g} s, pongs counted at the driver "
      "(pongs/s and payload MB/s of the pongs, first write to last pong)\n\n",
      info.domain_id, info.qos_file,
      info.fastdds_profile.empty() ? "UDPv4 only (the processes' default)"
                                   : "Fast DDS profile " + info.fastdds_profile,
      info.echo_prefix.empty() ? "" : ", echo run under '" + info.echo_prefix + "'",
      info.rounds, info.samples, info.large_samples, info.sample_timeout_s, info.throughput_s);
}

}  // namespace

void PrintTable(std::ostream& out, const RunInfo& info, const std::vector<CaseResult>& results) {
  PrintHeader(out, info);
  out << fmt::format("{:<8} {:<7} {:>7} {:>7} {:>5} {:>9} {:>9} {:>8} {:>8} {:>9} {:>8}\n",
                     "impl", "profile", "bytes", "samples", "lost", "p50_us", "p99_us",
                     "tp_sent", "tp_recv", "pongs/s", "MB/s");
  for (const CaseResult& r : results) {
    out << fmt::format(
        "{:<8} {:<7} {:>7} {:>7} {:>5} {:>9.1f} {:>9.1f} {:>8} {:>8} {:>9.0f} {:>8.2f}\n",
        ToString(r.impl), r.profile, r.bytes, r.samples, r.lost, r.p50_us, r.p99_us,
        r.tput_sent, r.tput_received, r.PongsPerSecond(), r.PayloadMegabytesPerSecond());
  }
  out << "\nmedian one-way latency overhead of runtime vs raw:\n";
  for (const auto& [profile, bytes] : Cases(results)) {
    const std::optional<double> pct = MedianOverheadPercent(results, profile, bytes);
    out << fmt::format("  {:<7} {:>7} B: {}\n", profile, bytes,
                       pct ? fmt::format("{:+.1f} %", *pct) : std::string("n/a"));
  }
}

nlohmann::json ToJson(const RunInfo& info, const std::vector<CaseResult>& results) {
  nlohmann::json j;
  j["setup"] = {{"domain", info.domain_id},
                {"rounds", info.rounds},
                {"qos_file", info.qos_file},
                {"fastdds_profile", info.fastdds_profile},
                {"echo_prefix", info.echo_prefix},
                {"samples", info.samples},
                {"large_samples", info.large_samples},
                {"throughput_s", info.throughput_s},
                {"sample_timeout_s", info.sample_timeout_s},
                {"latency", "one-way = round trip / 2"},
                {"throughput", "pongs received at the driver while pinging back to back"}};
  j["results"] = nlohmann::json::array();
  for (const CaseResult& r : results) {
    j["results"].push_back({{"impl", ToString(r.impl)},
                            {"profile", r.profile},
                            {"bytes", r.bytes},
                            {"samples", r.samples},
                            {"lost", r.lost},
                            {"p50_us", r.p50_us},
                            {"p99_us", r.p99_us},
                            {"throughput_sent", r.tput_sent},
                            {"throughput_received", r.tput_received},
                            {"throughput_seconds", r.tput_seconds},
                            {"pongs_per_s", r.PongsPerSecond()},
                            {"payload_mb_per_s", r.PayloadMegabytesPerSecond()}});
  }
  j["median_overhead_percent"] = nlohmann::json::array();
  for (const auto& [profile, bytes] : Cases(results)) {
    const std::optional<double> pct = MedianOverheadPercent(results, profile, bytes);
    j["median_overhead_percent"].push_back(
        {{"profile", profile}, {"bytes", bytes},
         {"runtime_vs_raw", pct ? nlohmann::json(*pct) : nlohmann::json(nullptr)}});
  }
  return j;
}

}  // namespace stickrep::runtime::bench
