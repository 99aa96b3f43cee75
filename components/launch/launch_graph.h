#pragma once

#include <map>
#include <string>
#include <vector>

#include "common/strict_yaml.h"

namespace stickrep::launch {

// One process of a deployment.
struct ProcessSpec {
  std::string name;
  std::string executable;         // looked up next to stickrep-launch, then on PATH
  std::vector<std::string> args;  // placeholders are substituted (see LaunchGraph)
  bool use_common_args = true;    // append the graph's common_args (false: not a StickRep
                                  // process, e.g. the discovery server)
};

// A process graph (deploy/*.yaml): which processes run together on one host, and when the
// run ends. Arguments may use {graph_dir}, {config_dir} and the graph's `parameters`
// ({discovery_server}, ...), whose defaults `stickrep-launch --set NAME=VALUE` overrides.
struct LaunchGraph {
  std::string file;
  std::string name;
  std::map<std::string, std::string> parameters;  // name -> default value
  std::vector<std::string> common_args;           // appended to every StickRep process
  std::vector<ProcessSpec> processes;
  std::string until_exit_of;      // the run ends when this process exits (empty: never)
  double max_duration_s = 0.0;    // and in any case after this long (0: no limit)
  double start_spacing_s = 0.0;   // pause between starting processes

  // Throws InputError naming file, line and key.
  static LaunchGraph Load(const StrictYaml& root);
  static LaunchGraph LoadFile(const std::string& path);
};

// Replaces every {name} of `values` in `arg`; throws InputError for a {name} it does not know.
std::string SubstitutePlaceholders(const std::string& arg,
                                   const std::map<std::string, std::string>& values);

// The values placeholders take: graph_dir, config_dir, then the graph's parameters with
// `overrides` ("NAME=VALUE" each) applied; a parameter's value may use {graph_dir} and
// {config_dir}. Throws InputError naming an override that is
// malformed or names no parameter of the graph.
std::map<std::string, std::string> PlaceholderValues(const LaunchGraph& graph,
                                                     const std::string& config_dir,
                                                     const std::vector<std::string>& overrides);

}  // namespace stickrep::launch
