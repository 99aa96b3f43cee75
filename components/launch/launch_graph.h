#pragma once

#include <string>
#include <vector>

#include "common/strict_yaml.h"

namespace stickrep::launch {

// One process of a deployment.
struct ProcessSpec {
  std::string name;
  std::string executable;         // looked up next to stickrep-launch, then on PATH
  std::vector<std::string> args;  // {graph_dir} and {config_dir} are substituted
};

// A process graph (deploy/*.yaml): which processes run together on one host, and when the
// run ends.
struct LaunchGraph {
  std::string file;
  std::string name;
  std::vector<ProcessSpec> processes;
  std::string until_exit_of;      // the run ends when this process exits (empty: never)
  double max_duration_s = 0.0;    // and in any case after this long (0: no limit)
  double start_spacing_s = 0.0;   // pause between starting processes

  // Throws InputError naming file, line and key.
  static LaunchGraph Load(const StrictYaml& root);
  static LaunchGraph LoadFile(const std::string& path);
};

// Replaces {graph_dir} and {config_dir} in `arg`.
std::string SubstitutePlaceholders(const std::string& arg, const std::string& graph_dir,
                                   const std::string& config_dir);

}  // namespace stickrep::launch
