#include "launch/launcher.h"

#include "launch/child_process.h"
#include "launch/handshake_watch.h"

#include <poll.h>
#include <signal.h>

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <atomic>
#include <cstring>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <thread>

namespace stickrep::launch {

namespace {

std::atomic<bool> g_stop_requested{false};
void OnSignal(int) { g_stop_requested = true; }

std::string FindExecutable(const std::string& exe, const std::string& bin_dir) {
  if (exe.find('/') != std::string::npos) return exe;
  const std::filesystem::path beside = std::filesystem::path(bin_dir) / exe;
  if (std::filesystem::exists(beside)) return beside.string();
  return exe;  // execvp searches PATH
}

using SteadyClock = std::chrono::steady_clock;

// Restarts per pair of processes for a stuck DDS Security handshake: a pair still stuck after
// these is left as it is (its processes' logs show which participants they authenticated).
constexpr int kMaxHandshakeHeals = 3;

double SecondsBetween(SteadyClock::time_point a, SteadyClock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

// One process of the graph across its restarts.
struct Child {
  const ProcessSpec* spec = nullptr;
  std::vector<std::string> argv;
  std::unique_ptr<ChildProcess> process;
  ProcessResult result;
  SteadyClock::time_point started;
  bool down = false;                      // ended, and no restart is due
  std::optional<SteadyClock::time_point> restart_at;
  int in_a_row = 0;                       // restarts since it last stayed up backoff_max_s
  bool healing = false;                   // stopped by the launcher to be started again
};

// What the run watches across rounds: the clock it started on (its time limit counts from
// there) and, when secured, the processes' DDS Security handshakes.
struct Watch {
  SteadyClock::time_point started = SteadyClock::now();
  std::optional<HandshakeWatch> handshakes;
  double Now() const { return SecondsBetween(started, SteadyClock::now()); }
};

void Forward(Child& c, std::ostream& out, size_t width, bool flush_partial,
             Watch* watch = nullptr) {
  for (const std::string& line : c.process->ReadLines(flush_partial)) {
    fmt::print(out, "{:<{}} | {}\n", c.result.name, width, line);
    if (watch != nullptr && watch->handshakes) watch->handshakes->Line(c.result.name, line);
    const auto pos = line.find("stopped: ");
    if (pos != std::string::npos) c.result.last_summary = line.substr(pos + 9);
  }
  out.flush();
}

bool Reap(Child& c) {
  if (!c.process->Exited()) return false;
  c.result.exit_code = c.process->exit_code();
  c.result.signal = c.process->term_signal();
  return true;
}

std::string HowItEnded(const ProcessResult& r) {
  return r.signal != 0 ? fmt::format("was killed by signal {} ({})", r.signal, strsignal(r.signal))
                       : fmt::format("exited with code {}", r.exit_code);
}

// The command line of one process: its arguments, the graph's parameters substituted.
std::vector<std::string> CommandLine(const LaunchGraph& graph, const ProcessSpec& p,
                                     const LaunchOptions& options,
                                     const std::map<std::string, std::string>& values) {
  std::vector<std::string> args{FindExecutable(p.executable, options.bin_dir)};
  for (const std::string& a : p.args) args.push_back(SubstitutePlaceholders(a, values));
  if (p.use_common_args) {
    for (const std::string& a : graph.common_args) {
      args.push_back(SubstitutePlaceholders(a, values));
    }
    args.insert(args.end(), options.extra_args.begin(), options.extra_args.end());
    if (!options.security_dir.empty()) {
      args.insert(args.end(), {"--security-dir", options.security_dir});
    }
  }
  if (!options.security_dir.empty()) {
    for (const std::string& a : p.secure_args) args.push_back(SubstitutePlaceholders(a, values));
  }
  return args;
}

// Starts every process of the graph.
std::vector<Child> StartChildren(const LaunchGraph& graph, const LaunchOptions& options,
                                 Watch& watch) {
  const auto values =
      PlaceholderValues(graph, options.config_dir, options.overrides, options.security_dir);
  std::vector<Child> children;
  for (const ProcessSpec& p : graph.processes) {
    Child c;
    c.spec = &p;
    c.argv = CommandLine(graph, p, options, values);
    c.result.name = p.name;
    c.process = std::make_unique<ChildProcess>(p.name, c.argv);
    c.started = SteadyClock::now();
    if (watch.handshakes) watch.handshakes->Started(p.name, watch.Now());
    children.push_back(std::move(c));
    if (graph.start_spacing_s > 0.0) {
      std::this_thread::sleep_for(std::chrono::duration<double>(graph.start_spacing_s));
    }
  }
  return children;
}

// A process ended while the run goes on: schedules its restart if its policy says so, with
// the back-off, or leaves it down; says which.
void DecideRestart(Child& c, std::ostream& out) {
  const RestartPolicy& policy = c.spec->restart;
  const ProcessResult& r = c.result;
  const bool failed = r.signal != 0 || r.exit_code != 0;
  const double ran_s = SecondsBetween(c.started, SteadyClock::now());
  const bool wanted = policy.when == RestartPolicy::When::kAlways ||
                      (policy.when == RestartPolicy::When::kOnFailure && failed);
  if (!wanted || (policy.max_restarts > 0 && r.restarts >= policy.max_restarts)) {
    fmt::print(out, "launch: {} {} after {:.1f} s; it stays down ({})\n", r.name, HowItEnded(r),
               ran_s,
               wanted ? fmt::format("{} restarts were allowed", policy.max_restarts)
                      : fmt::format("restart policy {}", ToString(policy.when)));
    c.down = true;
    return;
  }
  if (ran_s >= policy.backoff_max_s) c.in_a_row = 0;
  const double delay_s =
      std::min(policy.backoff_max_s, policy.backoff_initial_s * std::pow(2.0, c.in_a_row));
  c.in_a_row++;
  c.restart_at = SteadyClock::now() + std::chrono::duration_cast<SteadyClock::duration>(
                                          std::chrono::duration<double>(delay_s));
  fmt::print(out, "launch: {} {} after {:.1f} s: restarting it in {:.2f} s (restart {}{})\n",
             r.name, HowItEnded(r), ran_s, delay_s, r.restarts + 1,
             policy.max_restarts > 0 ? fmt::format(" of {}", policy.max_restarts) : "");
}

void Restart(Child& c, std::ostream& out, Watch& watch) {
  c.restart_at.reset();
  c.process = std::make_unique<ChildProcess>(c.result.name, c.argv);
  c.started = SteadyClock::now();
  c.result.restarts++;
  c.result.exit_code = -1;
  c.result.signal = 0;
  if (watch.handshakes) watch.handshakes->Started(c.result.name, watch.Now());
  fmt::print(out, "launch: {} restarted (restart {})\n", c.result.name, c.result.restarts);
}

bool Running(const Child& c) { return !c.down && !c.restart_at; }

// Secured runs: a pair of processes stuck in their DDS Security handshake gets its later
// process stopped (SIGTERM) and started again as soon as it has ended, whatever its policy.
void HealHandshakes(std::vector<Child>& children, std::ostream& out, Watch& watch) {
  if (!watch.handshakes) return;
  for (const HandshakeWatch::Stuck& s : watch.handshakes->Check(watch.Now())) {
    for (Child& c : children) {
      if (c.result.name != s.restart || !Running(c) || c.healing) continue;
      fmt::print(out,
                 "launch: {} and {} have not authenticated each other {:.0f} s after both "
                 "started (a DDS Security handshake that never completed): restarting {}\n",
                 s.restart, s.other, s.together_s, s.restart);
      c.healing = true;
      c.process->Signal(SIGTERM);
    }
  }
}

// One round of the run: forwards output, reaps what ended, restarts what is due. Returns why
// the run must end, or "".
std::string Step(const LaunchGraph& graph, std::vector<Child>& children, std::ostream& out,
                 size_t width, Watch& watch) {
  std::string ended_by;
  for (Child& c : children) {
    if (c.restart_at && SteadyClock::now() >= *c.restart_at) Restart(c, out, watch);
    if (!Running(c)) continue;
    Forward(c, out, width, false, &watch);
    if (!Reap(c)) continue;
    Forward(c, out, width, true, &watch);
    if (watch.handshakes) watch.handshakes->Stopped(c.result.name);
    if (c.healing) {
      c.healing = false;
      c.restart_at = SteadyClock::now();
      continue;
    }
    const bool failed = c.result.signal != 0 || c.result.exit_code != 0;
    if (failed) c.result.failures++;
    const bool ends_the_run = c.result.name == graph.until_exit_of;
    if (c.result.exit_code == 2 && c.result.signal == 0) {
      ended_by = c.result.name + " refused its input (exit code 2)";
      c.down = true;
    } else if (ends_the_run && !failed) {
      ended_by = c.result.name + " exited";  // done: never restarted
      c.down = true;
    } else {
      DecideRestart(c, out);
      if (ends_the_run && c.down) ended_by = c.result.name + " exited";
    }
  }
  if (std::all_of(children.begin(), children.end(), [](const Child& c) { return c.down; })) {
    // Keeps the reason a process gave, when it gave one in the same round.
    ended_by = ended_by.empty() ? "every process exited" : "every process exited; " + ended_by;
  }
  HealHandshakes(children, out, watch);
  return ended_by;
}

// SIGTERM to every process still running, SIGKILL to those still there after the grace.
void StopChildren(std::vector<Child>& children, const LaunchOptions& options, std::ostream& out,
                  size_t width) {
  for (Child& c : children) {
    if (Running(c)) c.process->Signal(SIGTERM);
  }
  const auto deadline = SteadyClock::now() +
                        std::chrono::duration_cast<SteadyClock::duration>(
                            std::chrono::duration<double>(options.stop_grace_s));
  for (;;) {
    bool all_done = true;
    for (Child& c : children) {
      if (!Running(c)) continue;
      Forward(c, out, width, false);
      all_done &= Reap(c);
    }
    if (all_done) break;
    if (SteadyClock::now() > deadline) {
      for (Child& c : children) {
        if (Running(c) && !c.process->Exited()) {
          fmt::print(out, "{} did not stop within {:g} s: killing it\n", c.result.name,
                     options.stop_grace_s);
          c.process->Signal(SIGKILL);
          c.process->WaitExit(5.0);
          Reap(c);
        }
      }
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

}  // namespace

std::vector<ProcessResult> RunGraph(const LaunchGraph& graph, const LaunchOptions& options,
                                    std::ostream& out) {
  struct sigaction sa {};
  sa.sa_handler = OnSignal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  signal(SIGPIPE, SIG_IGN);

  size_t width = 0;
  for (const ProcessSpec& p : graph.processes) width = std::max(width, p.name.size());
  Watch watch;
  if (!options.security_dir.empty() && graph.handshake_timeout_s > 0.0) {
    watch.handshakes.emplace(graph.handshake_timeout_s, kMaxHandshakeHeals);
  }
  std::vector<Child> children = StartChildren(graph, options, watch);
  fmt::print(out, "started {} processes of '{}'{}\n", children.size(), graph.name,
             options.security_dir.empty() ? "" : " (secured: " + options.security_dir + ")");

  std::string ended_by;
  while (ended_by.empty()) {
    std::vector<pollfd> fds;
    for (const Child& c : children) {
      if (Running(c)) fds.push_back({c.process->output_fd(), POLLIN, 0});
    }
    poll(fds.data(), fds.size(), 100);
    ended_by = Step(graph, children, out, width, watch);
    const double elapsed = watch.Now();
    if (ended_by.empty() && graph.max_duration_s > 0.0 && elapsed > graph.max_duration_s) {
      ended_by = fmt::format("the {:g} s limit passed", graph.max_duration_s);
    }
    if (ended_by.empty() && g_stop_requested) ended_by = "a stop was requested";
  }
  fmt::print(out, "ending the run: {}\n", ended_by);
  StopChildren(children, options, out, width);
  std::vector<ProcessResult> results;
  for (Child& c : children) {
    if (c.process->Exited()) Forward(c, out, width, true);
    results.push_back(c.result);
  }
  return results;
}

void PrintResults(const std::vector<ProcessResult>& results, std::ostream& out) {
  size_t width = 7;
  for (const auto& r : results) width = std::max(width, r.name.size());
  fmt::print(out, "\n{:<{}}  {:<9}  {:<8}  {}\n", "PROCESS", width, "EXIT", "RESTARTS",
             "SUMMARY");
  for (const auto& r : results) {
    const std::string how =
        r.signal != 0 ? fmt::format("signal {}", r.signal) : fmt::format("{}", r.exit_code);
    fmt::print(out, "{:<{}}  {:<9}  {:<8}  {}\n", r.name, width, how, r.restarts,
               r.last_summary.empty() ? "-" : r.last_summary);
  }
}

}  // namespace stickrep::launch
