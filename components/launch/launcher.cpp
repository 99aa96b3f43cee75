#include "launch/launcher.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <ostream>
#include <stdexcept>
#include <thread>

namespace stickrep::launch {

namespace {

std::atomic<bool> g_stop_requested{false};
void OnSignal(int) { g_stop_requested = true; }

struct Child {
  std::string name;
  pid_t pid = -1;
  int out_fd = -1;       // the child's stdout and stderr, merged
  std::string partial;   // an incomplete last line
  bool running = true;
  ProcessResult result;
};

std::string FindExecutable(const std::string& exe, const std::string& bin_dir) {
  if (exe.find('/') != std::string::npos) return exe;
  const std::filesystem::path beside = std::filesystem::path(bin_dir) / exe;
  if (std::filesystem::exists(beside)) return beside.string();
  return exe;  // execvp searches PATH
}

Child Spawn(const ProcessSpec& spec, const std::vector<std::string>& args) {
  int fds[2];
  if (pipe(fds) != 0) throw std::runtime_error("pipe() failed");
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork() failed");
  if (pid == 0) {
    dup2(fds[1], STDOUT_FILENO);
    dup2(fds[1], STDERR_FILENO);
    close(fds[0]);
    close(fds[1]);
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execvp(argv[0], argv.data());
    fmt::print(stderr, "cannot start {}: {}\n", args[0], std::strerror(errno));
    _exit(127);
  }
  close(fds[1]);
  fcntl(fds[0], F_SETFL, O_NONBLOCK);
  Child c;
  c.name = spec.name;
  c.pid = pid;
  c.out_fd = fds[0];
  c.result.name = spec.name;
  return c;
}

void Forward(Child& c, std::ostream& out, size_t width, bool flush_partial) {
  char buf[4096];
  for (;;) {
    const ssize_t n = read(c.out_fd, buf, sizeof(buf));
    if (n <= 0) break;
    c.partial.append(buf, static_cast<size_t>(n));
  }
  size_t start = 0;
  for (size_t nl = c.partial.find('\n'); nl != std::string::npos;
       nl = c.partial.find('\n', start)) {
    const std::string line = c.partial.substr(start, nl - start);
    fmt::print(out, "{:<{}} | {}\n", c.name, width, line);
    const auto pos = line.find("stopped: ");
    if (pos != std::string::npos) c.result.last_summary = line.substr(pos + 9);
    start = nl + 1;
  }
  c.partial.erase(0, start);
  if (flush_partial && !c.partial.empty()) {
    fmt::print(out, "{:<{}} | {}\n", c.name, width, c.partial);
    c.partial.clear();
  }
  out.flush();
}

bool Reap(Child& c, bool block) {
  if (!c.running) return true;
  int status = 0;
  const pid_t r = waitpid(c.pid, &status, block ? 0 : WNOHANG);
  if (r != c.pid) return false;
  c.running = false;
  if (WIFEXITED(status)) c.result.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) c.result.signal = WTERMSIG(status);
  return true;
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

  const std::string graph_dir = std::filesystem::path(graph.file).parent_path().string();
  size_t width = 0;
  for (const ProcessSpec& p : graph.processes) width = std::max(width, p.name.size());
  std::vector<Child> children;
  const auto started = std::chrono::steady_clock::now();
  for (const ProcessSpec& p : graph.processes) {
    std::vector<std::string> args{FindExecutable(p.executable, options.bin_dir)};
    for (const std::string& a : p.args) {
      args.push_back(SubstitutePlaceholders(a, graph_dir, options.config_dir));
    }
    args.insert(args.end(), options.extra_args.begin(), options.extra_args.end());
    children.push_back(Spawn(p, args));
    if (graph.start_spacing_s > 0.0) {
      std::this_thread::sleep_for(std::chrono::duration<double>(graph.start_spacing_s));
    }
  }
  fmt::print(out, "started {} processes of '{}'\n", children.size(), graph.name);

  std::string ended_by;
  while (ended_by.empty()) {
    std::vector<pollfd> fds;
    for (const Child& c : children) fds.push_back({c.out_fd, POLLIN, 0});
    poll(fds.data(), fds.size(), 100);
    for (Child& c : children) {
      Forward(c, out, width, false);
      if (Reap(c, false) && c.name == graph.until_exit_of) ended_by = c.name + " exited";
    }
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    if (graph.max_duration_s > 0.0 && elapsed > graph.max_duration_s) {
      ended_by = fmt::format("the {:g} s limit passed", graph.max_duration_s);
    }
    if (g_stop_requested) ended_by = "a stop was requested";
    if (std::all_of(children.begin(), children.end(), [](const Child& c) { return !c.running; })) {
      ended_by = "every process exited";
    }
  }
  fmt::print(out, "ending the run: {}\n", ended_by);
  for (Child& c : children) {
    if (c.running) kill(c.pid, SIGTERM);
  }
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(options.stop_grace_s));
  for (;;) {
    bool all_done = true;
    for (Child& c : children) {
      Forward(c, out, width, false);
      all_done &= Reap(c, false);
    }
    if (all_done) break;
    if (std::chrono::steady_clock::now() > deadline) {
      for (Child& c : children) {
        if (c.running) {
          fmt::print(out, "{} did not stop within {:g} s: killing it\n", c.name,
                     options.stop_grace_s);
          kill(c.pid, SIGKILL);
          Reap(c, true);
        }
      }
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  std::vector<ProcessResult> results;
  for (Child& c : children) {
    Forward(c, out, width, true);
    close(c.out_fd);
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
