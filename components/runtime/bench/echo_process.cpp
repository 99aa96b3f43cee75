#include "runtime/bench/echo_process.h"

#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace stickrep::runtime::bench {

std::vector<std::string> SplitWords(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

std::string SelfExecutable() {
  // /proc/PID/exe rather than /proc/self/exe: under a prefix command "self" would be the
  // prefix; and rather than the resolved path: it still works if the file was replaced
  // (rebuilt) while this process runs.
  return "/proc/" + std::to_string(getpid()) + "/exe";
}

EchoProcess::EchoProcess(const std::vector<std::string>& prefix,
                         const std::vector<std::string>& args) {
  // Everything the child needs is built before fork: after it only exec-safe calls run.
  std::vector<std::string> words = prefix;
  words.push_back(SelfExecutable());
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  const pid_t parent = getpid();

  pid_ = fork();
  if (pid_ < 0) throw std::runtime_error(std::string("fork failed: ") + std::strerror(errno));
  if (pid_ == 0) {
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) _exit(1);  // the parent died before prctl
    execvp(argv[0], argv.data());
    const char msg[] = "stickrep-transport-bench: could not start the echo process\n";
    (void)!write(STDERR_FILENO, msg, sizeof(msg) - 1);
    _exit(127);
  }
}

EchoProcess::~EchoProcess() {
  if (pid_ > 0 && !exited_) Stop(5.0);
}

bool EchoProcess::Reap(bool block) {
  if (exited_) return true;
  const pid_t r = waitpid(pid_, &status_, block ? 0 : WNOHANG);
  if (r == pid_) exited_ = true;
  return exited_;
}

std::optional<std::string> EchoProcess::ExitState() {
  if (!Reap(false)) return std::nullopt;
  if (WIFSIGNALED(status_)) return "was killed by signal " + std::to_string(WTERMSIG(status_));
  return "exited with code " + std::to_string(WEXITSTATUS(status_));
}

int EchoProcess::Stop(double timeout_s) {
  if (!Reap(false)) {
    kill(pid_, SIGTERM);
    const auto until = std::chrono::steady_clock::now() +
                       std::chrono::milliseconds(static_cast<int>(timeout_s * 1000));
    while (!Reap(false) && std::chrono::steady_clock::now() < until) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    if (!exited_) {
      kill(pid_, SIGKILL);
      Reap(true);
    }
  }
  return WIFSIGNALED(status_) ? 128 + WTERMSIG(status_) : WEXITSTATUS(status_);
}

}  // namespace stickrep::runtime::bench
