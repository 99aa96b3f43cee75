#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

namespace stickrep::launch {

// Fast DDS 2.9's DDS Security handshake between two participants now and then never
// completes: neither authenticates the other, neither reports a failure, and they never
// exchange a sample (in the secured all-in-one graph, 1 to 3 of 8 launches left one of the
// 21 pairs so; restarting either process of the pair let it authenticate at once —
// docs/security.md). The launcher watches its processes' own log lines for it: each
// secured process names its participant when it starts ("secured: identity 'sonar' of DIR
// (participant stickrep-sonar)") and every participant it authenticates ("DDS Security:
// participant PREFIX (stickrep-camera) authenticated"). A pair of the graph's processes that
// have both run for `timeout_s` without authenticating each other is stuck, and the
// later-started of the two is to be restarted (at most `max_heals` times per pair).
class HandshakeWatch {
 public:
  HandshakeWatch(double timeout_s, int max_heals);

  // A process (re)started at `now_s`: what it had authenticated is forgotten.
  void Started(const std::string& process, double now_s);
  // A process is not running (ended; a restart calls Started again).
  void Stopped(const std::string& process);
  // One line of a process's output.
  void Line(const std::string& process, const std::string& line);

  struct Stuck {
    std::string restart;  // the process to restart: the later-started of the pair
    std::string other;
    double together_s = 0.0;  // how long both have run
  };
  // The pairs stuck at `now_s`, each reported once per start of its later process.
  std::vector<Stuck> Check(double now_s);

 private:
  struct Process {
    bool running = false;
    double started_s = 0.0;
    std::string participant;             // from its "secured: identity" line
    std::set<std::string> authenticated; // participant names
  };
  bool Authenticated(const Process& a, const Process& b) const;

  double timeout_s_;
  int max_heals_;
  std::map<std::string, Process> processes_;
  std::map<std::pair<std::string, std::string>, int> heals_;  // by pair (sorted names)
};

}  // namespace stickrep::launch
