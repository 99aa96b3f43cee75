#pragma once

#include <map>
#include <string>
#include <vector>

#include "common/strict_yaml.h"

namespace stickrep::launch {

// What stickrep-launch does when a process ends while the run goes on: start it again after
// a back-off that doubles with every restart in a row, up to a limit. A process that exits
// with code 2 (bad input) is never restarted: the run ends, as its input will not get better.
struct RestartPolicy {
  enum class When { kNever, kOnFailure, kAlways };
  When when = When::kNever;        // on-failure: killed by a signal or a non-zero exit code
  double backoff_initial_s = 0.5;  // the first restart's delay, doubled for each one in a row
  double backoff_max_s = 8.0;      // the longest delay; a process that then stays up this
                                   // long starts the back-off over
  int max_restarts = 10;           // restarts in the whole run, then it stays down (0: no limit)
};
const char* ToString(RestartPolicy::When when);

// One process of a deployment.
struct ProcessSpec {
  std::string name;
  std::string executable;         // looked up next to stickrep-launch, then on PATH
  std::vector<std::string> args;  // placeholders are substituted (see LaunchGraph)
  bool use_common_args = true;    // append the graph's common_args (false: not a StickRep
                                  // process, e.g. the discovery server)
  // Appended only when the run is secured (stickrep-launch --security-dir DIR; {security_dir}
  // is DIR): for a process that is not a StickRep process, which gets no --security-dir.
  std::vector<std::string> secure_args;
  RestartPolicy restart;          // the graph's `restart`, or the process's own
};

// A process graph (deploy/*.yaml): which processes run together on one host, when the run
// ends and what happens to a process that ends before it (`restart`, for the whole graph and
// per process: `restart: on-failure` or `restart: {policy: on-failure, backoff_initial_s:
// 0.5, backoff_max_s: 8, max_restarts: 10}`; default never). Arguments may use {graph_dir},
// {config_dir}, {security_dir} and the graph's `parameters` ({discovery_server}, ...), whose
// defaults `stickrep-launch --set NAME=VALUE` overrides.
struct LaunchGraph {
  std::string file;
  std::string name;
  std::map<std::string, std::string> parameters;  // name -> default value
  std::vector<std::string> common_args;           // appended to every StickRep process
  std::vector<ProcessSpec> processes;
  std::string until_exit_of;      // the run ends when this process exits with code 0, or
                                  // fails and is not restarted (empty: never)
  double max_duration_s = 0.0;    // and in any case after this long (0: no limit)
  double start_spacing_s = 0.0;   // pause between starting processes
  // Secured runs: two processes that have not authenticated each other this long after both
  // started are taken for a stuck DDS Security handshake, and the later one is restarted
  // (HandshakeWatch). 0: never.
  double handshake_timeout_s = 20.0;
  RestartPolicy restart;          // every process's, unless it names its own

  // Throws InputError naming file, line and key.
  static LaunchGraph Load(const StrictYaml& root);
  static LaunchGraph LoadFile(const std::string& path);
};

// Replaces every {name} of `values` in `arg`; throws InputError for a {name} it does not know.
std::string SubstitutePlaceholders(const std::string& arg,
                                   const std::map<std::string, std::string>& values);

// The values placeholders take: graph_dir, config_dir, security_dir, then the graph's
// parameters with `overrides` ("NAME=VALUE" each) applied; a parameter's value may use
// {graph_dir} and {config_dir}. Throws InputError naming an override that is
// malformed or names no parameter of the graph.
std::map<std::string, std::string> PlaceholderValues(const LaunchGraph& graph,
                                                     const std::string& config_dir,
                                                     const std::vector<std::string>& overrides,
                                                     const std::string& security_dir = "");

// The `restart` entry under `key` of `node` (a policy name, or a mapping of policy and
// back-off), over `defaults`. Throws InputError naming file, line and key.
RestartPolicy LoadRestartPolicy(const StrictYaml& node, const std::string& key,
                                RestartPolicy defaults);

}  // namespace stickrep::launch
