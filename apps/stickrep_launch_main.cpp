// stickrep-launch: runs a process graph (deploy/*.launch.yaml) and prints how it ended.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <csignal>
#include <filesystem>
#include <iostream>
#include <optional>

#include "common/config_paths.h"
#include "common/input_error.h"
#include "common/tool_main.h"
#include "launch/launcher.h"

int main(int argc, char** argv) {
  CLI::App app{"Start the StickRep processes of a deployment graph as separate processes"};
  std::string graph_file;
  int domain = -1;
  stickrep::launch::LaunchOptions options;
  options.bin_dir = std::filesystem::canonical("/proc/self/exe").parent_path().string();
  options.config_dir = stickrep::DefaultConfigDir();
  app.add_option("graph", graph_file, "process graph, e.g. deploy/virtual_robot.launch.yaml")
      ->required();
  app.add_option("--domain", domain, "DDS domain id passed to every process")
      ->check(CLI::Range(0, 232));
  app.add_option("--config-dir", options.config_dir, "directory substituted for {config_dir}");
  app.add_option("--set", options.overrides,
                 "NAME=VALUE: a parameter of the graph, e.g. discovery_server=10.0.0.1:11811");
  app.add_option("--security-dir", options.security_dir,
                 "run the graph secured (DDS Security) with the identities, governance and "
                 "permissions of this directory (deploy/security/make-keys.sh DIR makes it)")
      ->check(CLI::ExistingDirectory);
  if (const std::optional<int> rc = stickrep::ParseCommandLine(app, argc, argv)) return *rc;
  try {
    const auto graph = stickrep::launch::LaunchGraph::LoadFile(graph_file);
    if (domain >= 0) options.extra_args = {"--domain", std::to_string(domain)};
    if (!options.security_dir.empty()) {
      options.security_dir = std::filesystem::absolute(options.security_dir).string();
    }
    const auto results = stickrep::launch::RunGraph(graph, options, std::cout);
    stickrep::launch::PrintResults(results, std::cout);
    for (const auto& r : results) {
      if (r.exit_code == stickrep::kExitBadInput && r.signal == 0) return stickrep::kExitBadInput;
    }
    // A process that failed at any time, restarted or not, makes the run a failure.
    for (const auto& r : results) {
      if (r.signal == SIGKILL || (r.exit_code != 0 && r.signal == 0) || r.failures > 0) return 1;
    }
    return 0;
  } catch (const stickrep::InputError& e) {
    fmt::print(stderr, "stickrep-launch: {}\n", e.what());
    return stickrep::kExitBadInput;
  }
}
