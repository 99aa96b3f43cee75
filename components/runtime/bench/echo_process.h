#pragma once

#include <sys/types.h>

#include <optional>
#include <string>
#include <vector>

namespace stickrep::runtime::bench {

// This program run again as a child process (the echo side of the ping-pong), optionally
// behind a prefix command such as `ip netns exec NS`. The child gets SIGTERM if this
// process dies, and is stopped (SIGTERM, then SIGKILL) when the object goes away.
class EchoProcess {
 public:
  // `prefix`: words run before the program (may be empty); `args`: the program's options.
  // Throws std::runtime_error if fork fails.
  EchoProcess(const std::vector<std::string>& prefix, const std::vector<std::string>& args);
  ~EchoProcess();
  EchoProcess(const EchoProcess&) = delete;
  EchoProcess& operator=(const EchoProcess&) = delete;

  // "exited with code N" or "was killed by signal N" once the child has ended, else nullopt.
  std::optional<std::string> ExitState();
  // Sends SIGTERM, waits up to `timeout_s`, then SIGKILL; returns the exit code (128 +
  // signal for a signal).
  int Stop(double timeout_s);

 private:
  bool Reap(bool block);

  pid_t pid_ = -1;
  int status_ = 0;
  bool exited_ = false;
};

// The words of `text` split at blanks (no quoting).
std::vector<std::string> SplitWords(const std::string& text);

// A path that executes the running program's image.
std::string SelfExecutable();

}  // namespace stickrep::runtime::bench
