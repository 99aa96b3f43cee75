// stickrep-transport-bench: one-way latency and echoed throughput of Image samples sent
// through the runtime layer (Participant, Writer, Reader, Executor) and through a plain
// Fast DDS DataWriter/DataReader pair with the same QoS, between two processes.
//
// The driver (default role) starts this program again with `--role echo` (optionally under
// --echo-prefix, e.g. "ip netns exec NS"), which writes every sample of bench/ping back on
// bench/pong. For every implementation, QoS profile and payload size the driver sends pings
// one at a time (latency = round trip / 2), then back to back for a fixed time (pongs/s).

#include <CLI/CLI.hpp>
#include <fastdds/dds/log/Log.hpp>
#include <fastdds/dds/log/StdoutErrConsumer.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <optional>
#include <thread>
#include <tuple>

#include "common/config_paths.h"
#include "common/input_error.h"
#include "common/tool_main.h"
#include "runtime/bench/bench_link.h"
#include "runtime/bench/bench_report.h"
#include "runtime/bench/echo_process.h"
#include "runtime/bench/pong_sink.h"
#include "runtime/process.h"

namespace stickrep::runtime::bench {
namespace {

using Clock = std::chrono::steady_clock;

// Payloads above this many bytes get `large_samples` latency pings instead of `samples`.
constexpr std::size_t kLargePayload = 64 * 1024;
constexpr int kWarmUpPongs = 50;
constexpr double kWarmUpBudgetS = 10.0;

struct Options {
  std::string role = "driver";
  std::vector<std::string> impls{"runtime", "raw"};
  std::vector<std::string> profiles{"event", "camera"};
  std::vector<std::size_t> sizes{64, 4096, 256000};
  int rounds = 1;
  int samples = 2000;
  int large_samples = 500;
  double throughput_s = 2.0;
  double sample_timeout_s = 1.0;
  double match_timeout_s = 10.0;
  int domain = 90;
  std::string qos_file = DefaultConfigDir() + "/qos.yaml";
  std::string fastdds_profile;
  std::string echo_prefix;
  std::string security_dir;
  bool json = false;
};

double SecondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

Impl ParseImpl(const std::string& text) { return text == "raw" ? Impl::kRaw : Impl::kRuntime; }

// The bench catalog of one profile of the QoS file (InputError if the profile is unknown).
QosCatalog CatalogFor(const QosCatalog& file_catalog, const std::string& profile) {
  return BenchCatalog(file_catalog.Profile(profile), file_catalog.file());
}

// Echo role: writes every ping back as a pong (a copy of the sample, in both
// implementations) until SIGINT/SIGTERM.
int RunEcho(const Options& o) {
  InstallSignalHandlers();
  const QosCatalog catalog = CatalogFor(QosCatalog::LoadFile(o.qos_file), o.profiles.front());
  msgs::Image pong;
  std::atomic<PingPongLink*> ready{nullptr};
  std::unique_ptr<PingPongLink> link = MakeLink(
      ParseImpl(o.impls.front()),
      LinkConfig{o.domain, "stickrep-bench-echo", catalog, kPongTopic, kPingTopic,
                 o.fastdds_profile, o.security_dir},
      [&](const msgs::Image& ping) {
        PingPongLink* l = ready.load();
        if (l == nullptr) return;
        pong = ping;
        l->Send(pong);
      });
  ready = link.get();
  while (KeepRunning().load()) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ready = nullptr;
  link.reset();
  return 0;
}

// The echo's command line: same domain, QoS file and XML profile, one implementation and
// one profile.
std::vector<std::string> EchoArgs(const Options& o, Impl impl, const std::string& profile) {
  std::vector<std::string> args{"--role",     "echo",    "--impls",  ToString(impl),
                                "--profiles", profile,   "--domain", std::to_string(o.domain),
                                "--qos",      o.qos_file};
  if (!o.fastdds_profile.empty()) {
    args.insert(args.end(), {"--fastdds-profile", o.fastdds_profile});
  }
  if (!o.security_dir.empty()) args.insert(args.end(), {"--security-dir", o.security_dir});
  return args;
}

// Waits until the driver's writer and reader both match the echo; throws if the echo
// ends or `timeout_s` passes first.
void WaitForEcho(const PingPongLink& link, EchoProcess& echo, const Options& o) {
  const Clock::time_point t0 = Clock::now();
  while (!link.Matched()) {
    if (const auto state = echo.ExitState()) {
      throw std::runtime_error("the echo process " + *state + " before matching");
    }
    if (SecondsSince(t0) > o.match_timeout_s) {
      throw std::runtime_error(fmt::format(
          "no match with the echo on domain {} within {:g} s (bench/ping, bench/pong); "
          "without multicast between the hosts, pass --fastdds-profile with initial peers",
          o.domain, o.match_timeout_s));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::cerr << fmt::format("  matched the echo after {:.2f} s\n", SecondsSince(t0));
}

// One ping: its arrival time, or nullopt if DDS refused it or no pong came in time.
std::optional<Clock::time_point> PingOnce(PingPongLink& link, PongSink& sink,
                                          msgs::Image& ping, uint32_t id, double timeout_s) {
  ping.width_px(id);
  sink.Expect(id);
  if (!link.Send(ping)) return std::nullopt;
  return sink.Wait(timeout_s);
}

// Pings until kWarmUpPongs came back or the budget is spent; throws if none came back.
void WarmUp(PingPongLink& link, PongSink& sink, msgs::Image& ping, uint32_t& next_id) {
  const Clock::time_point t0 = Clock::now();
  int pongs = 0;
  while (pongs < kWarmUpPongs && SecondsSince(t0) < kWarmUpBudgetS) {
    if (PingOnce(link, sink, ping, ++next_id, 0.1)) pongs++;
  }
  if (pongs == 0) {
    throw std::runtime_error(fmt::format(
        "matched, but no {}-byte ping came back within {:g} s", ping.data().size(),
        kWarmUpBudgetS));
  }
}

// Latency phase: `samples` pings, each sent once the previous pong is back or timed out.
void MeasureLatency(PingPongLink& link, PongSink& sink, msgs::Image& ping, uint32_t& next_id,
                    double timeout_s, CaseResult& r) {
  for (int i = 0; i < r.samples; ++i) {
    const Clock::time_point t0 = Clock::now();
    const auto t1 = PingOnce(link, sink, ping, ++next_id, timeout_s);
    if (!t1) {
      r.lost++;
      continue;
    }
    r.one_way_us.push_back(std::chrono::duration<double, std::micro>(*t1 - t0).count() / 2.0);
  }
}

// Throughput phase: pings written back to back for `seconds`, then the pongs counted until
// all are back or none came for 0.5 s.
void MeasureThroughput(PingPongLink& link, PongSink& sink, msgs::Image& ping,
                       uint32_t& next_id, double seconds, CaseResult& r) {
  sink.CountFrom(next_id + 1);
  const Clock::time_point t0 = Clock::now();
  while (SecondsSince(t0) < seconds) {
    ping.width_px(++next_id);
    if (link.Send(ping)) r.tput_sent++;
  }
  const auto [received, last] = sink.FinishCounting(r.tput_sent, 0.5);
  r.tput_received = received;
  if (received > 0) r.tput_seconds = std::chrono::duration<double>(last - t0).count();
}

CaseResult RunCase(PingPongLink& link, PongSink& sink, uint32_t& next_id, const Options& o,
                   Impl impl, const std::string& profile, std::size_t bytes) {
  CaseResult r;
  r.impl = impl;
  r.profile = profile;
  r.bytes = bytes;
  r.samples = bytes > kLargePayload ? std::min(o.samples, o.large_samples) : o.samples;
  msgs::Image ping;
  ping.encoding("bench");
  ping.data().resize(bytes);
  for (std::size_t i = 0; i < bytes; ++i) ping.data()[i] = static_cast<uint8_t>(i);

  WarmUp(link, sink, ping, next_id);
  MeasureLatency(link, sink, ping, next_id, o.sample_timeout_s, r);
  MeasureThroughput(link, sink, ping, next_id, o.throughput_s, r);
  r.Summarise();
  std::cerr << fmt::format(
      "  {:>7} B: p50 {:.1f} us, p99 {:.1f} us, lost {}/{}; {} of {} pongs in {:.2f} s\n",
      bytes, r.p50_us, r.p99_us, r.lost, r.samples, r.tput_received, r.tput_sent,
      r.tput_seconds);
  return r;
}

// Every payload size for one implementation and profile, against a fresh echo process.
std::vector<CaseResult> RunImplProfile(const Options& o, Impl impl, const std::string& profile,
                                       const QosCatalog& catalog) {
  std::cerr << fmt::format("{} / {}: starting the echo\n", ToString(impl), profile);
  EchoProcess echo(SplitWords(o.echo_prefix), EchoArgs(o, impl, profile));
  PongSink sink;
  std::unique_ptr<PingPongLink> link =
      MakeLink(impl,
               LinkConfig{o.domain, "stickrep-bench-driver", catalog, kPingTopic, kPongTopic,
                          o.fastdds_profile, o.security_dir},
               [&sink](const msgs::Image& pong) { sink.OnPong(pong); });
  WaitForEcho(*link, echo, o);
  std::vector<CaseResult> results;
  uint32_t next_id = 0;
  for (std::size_t bytes : o.sizes) {
    results.push_back(RunCase(*link, sink, next_id, o, impl, profile, bytes));
  }
  link.reset();
  if (const int code = echo.Stop(5.0); code != 0) {
    std::cerr << fmt::format("warning: the echo process ended with code {}\n", code);
  }
  return results;
}

// Rows ordered by profile, then size, then implementation (runtime before raw).
void SortRows(const Options& o, std::vector<CaseResult>& rows) {
  const auto index = [](const auto& list, const auto& value) {
    return std::find(list.begin(), list.end(), value) - list.begin();
  };
  std::stable_sort(rows.begin(), rows.end(), [&](const CaseResult& a, const CaseResult& b) {
    return std::make_tuple(index(o.profiles, a.profile), index(o.sizes, a.bytes), a.impl) <
           std::make_tuple(index(o.profiles, b.profile), index(o.sizes, b.bytes), b.impl);
  });
}

// Adds one round's result to the row of the same case, or as a new row.
void AddRow(std::vector<CaseResult>& rows, const CaseResult& r) {
  for (CaseResult& row : rows) {
    if (row.impl == r.impl && row.profile == r.profile && row.bytes == r.bytes) {
      row.Merge(r);
      return;
    }
  }
  rows.push_back(r);
}

int RunDriver(const Options& o) {
  const QosCatalog file_catalog = QosCatalog::LoadFile(o.qos_file);
  std::vector<std::pair<std::string, QosCatalog>> catalogs;
  for (const std::string& p : o.profiles) catalogs.emplace_back(p, CatalogFor(file_catalog, p));
  std::vector<CaseResult> rows;
  for (int round = 0; round < o.rounds; ++round) {
    // Every other round runs the implementations in reverse order, so that a slow drift
    // of the machine's load does not always favour the same one.
    std::vector<std::string> impls = o.impls;
    if (round % 2 == 1) std::reverse(impls.begin(), impls.end());
    for (const auto& [profile, catalog] : catalogs) {
      for (const std::string& impl : impls) {
        for (const CaseResult& r : RunImplProfile(o, ParseImpl(impl), profile, catalog)) {
          AddRow(rows, r);
        }
      }
    }
  }
  for (CaseResult& r : rows) r.Summarise();
  SortRows(o, rows);
  const RunInfo info{o.domain,      o.rounds,        o.qos_file,     o.fastdds_profile,
                     o.echo_prefix, o.samples,       o.large_samples, o.throughput_s,
                     o.sample_timeout_s};
  // With --json, stdout carries only the JSON and the table goes to stderr.
  PrintTable(o.json ? std::cerr : std::cout, info, rows);
  if (o.json) std::cout << ToJson(info, rows).dump(2) << "\n";
  return 0;
}

void AddOptions(CLI::App& app, Options& o) {
  app.add_option("--role", o.role, "driver (default) or echo (started by the driver)")
      ->check(CLI::IsMember({"driver", "echo"}));
  app.add_option("--impls", o.impls, "implementations to compare")
      ->delimiter(',')
      ->check(CLI::IsMember({"runtime", "raw"}));
  app.add_option("--profiles", o.profiles, "QoS profiles of the QoS file to run")->delimiter(',');
  app.add_option("--sizes", o.sizes, "payload sizes in bytes")
      ->delimiter(',')
      ->check(CLI::Range(std::size_t{1}, std::size_t{16} * 1024 * 1024));
  app.add_option("--rounds", o.rounds, "times every case is run (results pooled)")
      ->check(CLI::Range(1, 100));
  app.add_option("--samples", o.samples, "latency pings per case")->check(CLI::Range(1, 10000000));
  app.add_option("--large-samples", o.large_samples, "latency pings for payloads above 64 kB")
      ->check(CLI::Range(1, 10000000));
  app.add_option("--throughput-seconds", o.throughput_s, "length of the throughput phase")
      ->check(CLI::Range(0.0, 600.0));
  app.add_option("--sample-timeout", o.sample_timeout_s, "seconds before a ping counts as lost")
      ->check(CLI::Range(0.001, 60.0));
  app.add_option("--match-timeout", o.match_timeout_s, "seconds to wait for the echo to match")
      ->check(CLI::Range(0.1, 600.0));
  app.add_option("--domain", o.domain, "DDS domain id")->check(CLI::Range(0, 232));
  app.add_option("--qos", o.qos_file, "QoS file whose profiles are used")
      ->check(CLI::ExistingFile);
  app.add_option("--fastdds-profile", o.fastdds_profile,
                 "Fast DDS XML file whose default participant profile both implementations "
                 "use (e.g. UDP only, initial peers)")
      ->check(CLI::ExistingFile);
  app.add_option("--security-dir", o.security_dir,
                 "DDS Security on both sides (deploy/security/make-keys.sh DIR; identity "
                 "'bench', whose topics are encrypted as commands and camera frames are)");
  app.add_option("--echo-prefix", o.echo_prefix,
                 "command the echo is run under, e.g. \"ip netns exec NS\"");
  app.add_flag("--json", o.json, "print JSON on stdout (the table then goes to stderr)");
}

int Main(int argc, char** argv) {
  CLI::App app{"Latency and throughput of the runtime layer against raw Fast DDS"};
  Options o;
  AddOptions(app, o);
  if (const std::optional<int> rc = ParseCommandLine(app, argc, argv)) return *rc;
  if (o.role == "echo" && (o.impls.size() != 1 || o.profiles.size() != 1)) {
    std::fprintf(stderr, "--role echo: needs exactly one --impls and one --profiles\n");
    return kExitBadInput;
  }
  // The echo may run in another directory context (ip netns exec): absolute paths.
  o.qos_file = std::filesystem::absolute(o.qos_file).string();
  if (!o.security_dir.empty()) o.security_dir = std::filesystem::absolute(o.security_dir).string();
  if (!o.fastdds_profile.empty()) {
    o.fastdds_profile = std::filesystem::absolute(o.fastdds_profile).string();
  }
  // Fast DDS logs to stdout by default; keep stdout for the results.
  auto consumer = std::make_unique<eprosima::fastdds::dds::StdoutErrConsumer>();
  consumer->stderr_threshold(eprosima::fastdds::dds::Log::Kind::Info);
  eprosima::fastdds::dds::Log::ClearConsumers();
  eprosima::fastdds::dds::Log::RegisterConsumer(std::move(consumer));
  try {
    if (!o.fastdds_profile.empty()) UseDefaultParticipantProfile(o.fastdds_profile);
    return o.role == "echo" ? RunEcho(o) : RunDriver(o);
  } catch (const InputError& e) {
    std::cerr << "stickrep-transport-bench: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "stickrep-transport-bench: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace
}  // namespace stickrep::runtime::bench

int main(int argc, char** argv) { return stickrep::runtime::bench::Main(argc, argv); }
