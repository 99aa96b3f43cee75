#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

namespace stickrep::launch {

// One child process with its stdout and stderr merged into a pipe that the parent reads
// without blocking. Used by stickrep-launch and by the multi-process tests. A child still
// running when this object is destroyed is killed.
class ChildProcess {
 public:
  // Starts argv[0] (searched on PATH if it has no '/'); throws std::runtime_error if the
  // process cannot be created. A program that cannot be executed exits with code 127.
  ChildProcess(std::string name, const std::vector<std::string>& argv);
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  const std::string& name() const { return name_; }
  pid_t pid() const { return pid_; }
  int output_fd() const { return fd_; }
  // Complete lines of output that arrived since the last call (and, with flush, the
  // incomplete last one). Everything read is also kept in output().
  std::vector<std::string> ReadLines(bool flush_partial = false);
  const std::string& output() const { return all_output_; }

  // True once the process has exited (non-blocking).
  bool Exited();
  void Signal(int sig);
  // Waits up to timeout_s for the process to exit; true if it did.
  bool WaitExit(double timeout_s);
  // Exit code, or -1 if it ended by a signal (see term_signal) or has not ended.
  int exit_code() const { return exit_code_; }
  int term_signal() const { return term_signal_; }

 private:
  std::string name_;
  pid_t pid_ = -1;
  int fd_ = -1;
  bool running_ = true;
  int exit_code_ = -1;
  int term_signal_ = 0;
  std::string partial_;
  std::string all_output_;
};

}  // namespace stickrep::launch
