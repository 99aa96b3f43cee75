#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "launch/launch_graph.h"

namespace stickrep::launch {

// How one process ended.
struct ProcessResult {
  std::string name;
  int exit_code = -1;        // -1: killed by a signal (see signal)
  int signal = 0;
  std::string last_summary;  // the process's last "stopped: ..." log line, if any
  int restarts = 0;          // how often the launcher started it again
  int failures = 0;          // how often it ended by a signal or a non-zero code (any instance)
};

struct LaunchOptions {
  std::string bin_dir;                 // where the StickRep executables are
  std::string config_dir;              // substituted for {config_dir}
  std::vector<std::string> extra_args; // appended to every StickRep process (--domain 5)
  double stop_grace_s = 10.0;          // SIGTERM, then SIGKILL after this long
  std::vector<std::string> overrides;  // "NAME=VALUE" for the graph's parameters (--set)
  // Secured run (--security-dir): every StickRep process gets --security-dir DIR, every
  // process its secure_args, and {security_dir} is DIR. Empty: plain DDS.
  std::string security_dir;
};

// Starts every process of the graph as its own child process, prefixes and forwards their
// output, restarts a process that ended as its restart policy says (with back-off; each
// restart is logged), ends the run when `until_exit_of` exits (cleanly, or failed and not to
// be restarted), a process exits with code 2
// (bad input), the time limit passes or SIGINT/SIGTERM arrives, then stops the rest with
// SIGTERM (SIGKILL after the grace period). Throws InputError for a bad --set.
std::vector<ProcessResult> RunGraph(const LaunchGraph& graph, const LaunchOptions& options,
                                    std::ostream& out);

// The closing table: process, how it ended, its restarts, its last summary line.
void PrintResults(const std::vector<ProcessResult>& results, std::ostream& out);

}  // namespace stickrep::launch
