#include "launch/launcher.h"

#include "launch/child_process.h"

#include <poll.h>
#include <signal.h>

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <algorithm>
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

struct Child {
  std::unique_ptr<ChildProcess> process;
  ProcessResult result;
};

void Forward(Child& c, std::ostream& out, size_t width, bool flush_partial) {
  for (const std::string& line : c.process->ReadLines(flush_partial)) {
    fmt::print(out, "{:<{}} | {}\n", c.result.name, width, line);
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

// Starts every process of the graph with its arguments, the graph's parameters substituted.
std::vector<Child> StartChildren(const LaunchGraph& graph, const LaunchOptions& options) {
  const auto values = PlaceholderValues(graph, options.config_dir, options.overrides);
  std::vector<Child> children;
  for (const ProcessSpec& p : graph.processes) {
    std::vector<std::string> args{FindExecutable(p.executable, options.bin_dir)};
    for (const std::string& a : p.args) args.push_back(SubstitutePlaceholders(a, values));
    if (p.use_common_args) {
      for (const std::string& a : graph.common_args) {
        args.push_back(SubstitutePlaceholders(a, values));
      }
      args.insert(args.end(), options.extra_args.begin(), options.extra_args.end());
    }
    Child c;
    c.result.name = p.name;
    c.process = std::make_unique<ChildProcess>(p.name, args);
    children.push_back(std::move(c));
    if (graph.start_spacing_s > 0.0) {
      std::this_thread::sleep_for(std::chrono::duration<double>(graph.start_spacing_s));
    }
  }
  return children;
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
  std::vector<Child> children = StartChildren(graph, options);
  const auto started = std::chrono::steady_clock::now();
  fmt::print(out, "started {} processes of '{}'\n", children.size(), graph.name);

  std::string ended_by;
  while (ended_by.empty()) {
    std::vector<pollfd> fds;
    for (const Child& c : children) fds.push_back({c.process->output_fd(), POLLIN, 0});
    poll(fds.data(), fds.size(), 100);
    for (Child& c : children) {
      Forward(c, out, width, false);
      if (!Reap(c)) continue;
      if (c.result.name == graph.until_exit_of) ended_by = c.result.name + " exited";
      if (c.result.exit_code == 2 && c.result.signal == 0) {
        ended_by = c.result.name + " refused its input (exit code 2)";
      }
    }
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    if (graph.max_duration_s > 0.0 && elapsed > graph.max_duration_s) {
      ended_by = fmt::format("the {:g} s limit passed", graph.max_duration_s);
    }
    if (g_stop_requested) ended_by = "a stop was requested";
    if (std::all_of(children.begin(), children.end(),
                    [](const Child& c) { return c.process->Exited(); })) {
      // Keeps the reason a process gave, when it gave one in the same round.
      ended_by = ended_by.empty() ? "every process exited"
                                  : "every process exited; " + ended_by;
    }
  }
  fmt::print(out, "ending the run: {}\n", ended_by);
  for (Child& c : children) c.process->Signal(SIGTERM);
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(options.stop_grace_s));
  for (;;) {
    bool all_done = true;
    for (Child& c : children) {
      Forward(c, out, width, false);
      all_done &= Reap(c);
    }
    if (all_done) break;
    if (std::chrono::steady_clock::now() > deadline) {
      for (Child& c : children) {
        if (!c.process->Exited()) {
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
  std::vector<ProcessResult> results;
  for (Child& c : children) {
    Forward(c, out, width, true);
    results.push_back(c.result);
  }
  return results;
}

void PrintResults(const std::vector<ProcessResult>& results, std::ostream& out) {
  size_t width = 7;
  for (const auto& r : results) width = std::max(width, r.name.size());
  fmt::print(out, "\n{:<{}}  {:<9}  {}\n", "PROCESS", width, "EXIT", "SUMMARY");
  for (const auto& r : results) {
    const std::string how =
        r.signal != 0 ? fmt::format("signal {}", r.signal) : fmt::format("{}", r.exit_code);
    fmt::print(out, "{:<{}}  {:<9}  {}\n", r.name, width, how,
               r.last_summary.empty() ? "-" : r.last_summary);
  }
}

}  // namespace stickrep::launch
