#include "launch/child_process.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <thread>

namespace stickrep::launch {

ChildProcess::ChildProcess(std::string name, const std::vector<std::string>& argv)
    : name_(std::move(name)) {
  if (argv.empty()) throw std::runtime_error("no program given for " + name_);
  int fds[2];
  if (pipe(fds) != 0) throw std::runtime_error("pipe() failed: " + std::string(strerror(errno)));
  // Signals are blocked across fork(): a SIGTERM meant for the child that arrived before
  // exec would otherwise run the parent's handler in the child and be lost. The child
  // restores the default dispositions, then unblocks, so such a signal takes effect.
  sigset_t all, previous;
  sigfillset(&all);
  sigprocmask(SIG_BLOCK, &all, &previous);
  const pid_t parent = getpid();
  pid_ = fork();
  if (pid_ == 0) {
    for (const int sig : {SIGINT, SIGTERM, SIGPIPE}) signal(sig, SIG_DFL);
    // A parent that dies, even by SIGKILL, takes its children along (SIGTERM: they stop
    // cleanly): a killed launcher (or test) leaves no process running on its domain. The
    // signal comes when the thread that forked ends: children are started from the thread
    // that supervises them to the end.
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) _exit(127);  // the parent died before the line above
    sigprocmask(SIG_SETMASK, &previous, nullptr);
    dup2(fds[1], STDOUT_FILENO);
    dup2(fds[1], STDERR_FILENO);
    close(fds[0]);
    close(fds[1]);
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execvp(args[0], args.data());
    std::fprintf(stderr, "cannot start %s: %s\n", args[0], strerror(errno));
    _exit(127);
  }
  sigprocmask(SIG_SETMASK, &previous, nullptr);
  if (pid_ < 0) throw std::runtime_error("fork() failed: " + std::string(strerror(errno)));
  close(fds[1]);
  fd_ = fds[0];
  fcntl(fd_, F_SETFL, O_NONBLOCK);
}

ChildProcess::~ChildProcess() {
  if (running_ && !Exited()) {
    Signal(SIGKILL);
    WaitExit(5.0);
  }
  if (fd_ >= 0) close(fd_);
}

std::vector<std::string> ChildProcess::ReadLines(bool flush_partial) {
  char buf[4096];
  for (;;) {
    const ssize_t n = read(fd_, buf, sizeof(buf));
    if (n <= 0) break;
    partial_.append(buf, static_cast<size_t>(n));
    all_output_.append(buf, static_cast<size_t>(n));
  }
  std::vector<std::string> lines;
  size_t start = 0;
  for (size_t nl = partial_.find('\n'); nl != std::string::npos; nl = partial_.find('\n', start)) {
    lines.push_back(partial_.substr(start, nl - start));
    start = nl + 1;
  }
  partial_.erase(0, start);
  if (flush_partial && !partial_.empty()) {
    lines.push_back(partial_);
    partial_.clear();
  }
  return lines;
}

bool ChildProcess::Exited() {
  if (!running_) return true;
  int status = 0;
  if (waitpid(pid_, &status, WNOHANG) != pid_) return false;
  running_ = false;
  if (WIFEXITED(status)) exit_code_ = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) term_signal_ = WTERMSIG(status);
  return true;
}

void ChildProcess::Signal(int sig) {
  if (running_) kill(pid_, sig);
}

bool ChildProcess::WaitExit(double timeout_s) {
  const auto until = std::chrono::steady_clock::now() +
                     std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                         std::chrono::duration<double>(timeout_s));
  while (!Exited()) {
    if (std::chrono::steady_clock::now() > until) return false;
    ReadLines();  // keep the pipe drained so the child never blocks on a full pipe
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return true;
}

}  // namespace stickrep::launch
