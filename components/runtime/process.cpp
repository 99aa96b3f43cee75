#include "runtime/process.h"

#include <CLI/CLI.hpp>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <optional>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "common/input_error.h"
#include "common/tool_main.h"
#include "runtime/deployment_options.h"
#include "runtime/endpoint.h"
#include "runtime/status_reporter.h"

namespace stickrep::runtime {

std::atomic<bool>& KeepRunning() {
  static std::atomic<bool> keep_running{true};
  return keep_running;
}

namespace {
void HandleSignal(int) { KeepRunning() = false; }
}  // namespace

void InstallSignalHandlers() {
  struct sigaction sa {};
  sa.sa_handler = HandleSignal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

int64_t WallClockNowNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

namespace {

// A process's command line.
struct ProcessOptions {
  std::string system_file;
  std::string config_file;
  int domain_override = -1;
  double run_for_s = 0.0;
  std::string log_level;
  DeploymentOptions deployment;
  std::vector<std::string> sets;  // --set KEY=VALUE over the config section
};

// Applies --set KEY=VALUE (KEY dotted into nested mappings, VALUE read as YAML) to the
// process's section of its config, before the section is checked: an unknown key is then
// refused like one written in the file.
void ApplySets(const StrictYaml& root, const std::string& name,
               const std::vector<std::string>& sets) {
  for (const std::string& set : sets) {
    const auto eq = set.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw InputError("--set", 0, set, "expected KEY=VALUE, e.g. --set real_time_factor=4");
    }
    YAML::Node node = root.raw()[name];
    const std::string key = set.substr(0, eq);
    std::size_t begin = 0;
    for (std::size_t dot; (dot = key.find('.', begin)) != std::string::npos; begin = dot + 1) {
      node.reset(node[key.substr(begin, dot - begin)]);
    }
    try {
      node[key.substr(begin)] = YAML::Load(set.substr(eq + 1));
    } catch (const YAML::Exception& e) {
      throw InputError("--set", 0, key, std::string("the value is not YAML: ") + e.what());
    }
  }
}

// Parses the command line; an exit code when the process must end at once (--help: 0, a
// bad command line: 2).
std::optional<int> ParseProcessOptions(int argc, char** argv, const std::string& name,
                                       ProcessOptions& o) {
  CLI::App app{"StickRep " + name + " process"};
  o.system_file = DefaultConfigDir() + "/system.yaml";
  o.config_file = DefaultConfigDir() + "/" + name + ".yaml";
  app.add_option("--system", o.system_file, "deployment settings (domain, QoS file, map, robot)");
  app.add_option("--config", o.config_file,
                 "this process's settings (top-level key '" + name + "')");
  app.add_option("--domain", o.domain_override, "DDS domain id, overriding the system file")
      ->check(CLI::Range(0, 232));
  app.add_option("--run-for", o.run_for_s, "stop by itself after this many seconds (0: run "
                                           "until SIGINT/SIGTERM)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--log-level", o.log_level, "trace, debug, info, warn or error")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error"}));
  AddDeploymentOptions(app, o.deployment);
  app.add_option("--set", o.sets,
                 "KEY=VALUE over this process's config section (dotted keys for nested ones; "
                 "repeatable)");
  return ParseCommandLine(app, argc, argv);
}

}  // namespace

int RunProcess(int argc, char** argv, const std::string& name, const NodeFactory& make_node) {
  ProcessOptions options;
  if (const auto code = ParseProcessOptions(argc, argv, name, options)) return *code;

  auto log = spdlog::stderr_color_mt(name);
  log->set_pattern("%H:%M:%S.%e [%n] %^%l%$ %v");
  InstallSignalHandlers();

  std::unique_ptr<SystemConfig> system;
  std::unique_ptr<Participant> participant;
  std::unique_ptr<ProcessNode> node;
  Executor executor;
  SampleCounters counters(log);
  try {
    system = std::make_unique<SystemConfig>(SystemConfig::LoadFile(options.system_file));
    if (options.domain_override >= 0) system->domain_id = options.domain_override;
    log->set_level(spdlog::level::from_str(options.log_level.empty() ? system->log_level
                                                                     : options.log_level));
    QosCatalog catalog = QosCatalog::LoadFile(system->qos_file);
    const StrictYaml config_root = StrictYaml::LoadFile(options.config_file);
    ApplySets(config_root, name, options.sets);
    const StrictYaml config = config_root.Child(name);
    config_root.Finish();

    participant = std::make_unique<Participant>(
        MakeParticipantConfig(*system, options.deployment, "stickrep-" + name),
        std::move(catalog));
    const std::string host = HostLabel(options.deployment);
    StatusReporter status(*participant, name, host, counters);
    NodeContext ctx{name,   *participant, executor,       log,  *system,
                    config, counters,     WallClockNowNs, host, [] { KeepRunning() = false; }};
    node = make_node();
    node->Configure(ctx);
    status.Publish(StatusReporter::State::kInactive, "configured");
    log->info("configured on domain {} on host '{}' ({})", system->domain_id, host,
              options.config_file);
    WatchDiscoveryServers(*participant, executor, log);
    if (!options.deployment.security_dir.empty()) {
      log->info("secured: identity '{}' of {} (participant stickrep-{})",
                participant->security_identity(), options.deployment.security_dir, name);
      WatchAuthentication(*participant, executor, log);
    }

    node->Activate();
    status.Publish(StatusReporter::State::kActive, "active");
    // The heartbeat says what last went wrong, so a console's `status` shows it.
    executor.AddTimer(kHeartbeatPeriodS, [&] {
      status.Publish(StatusReporter::State::kActive,
                     counters.last_warning().empty()
                         ? "active"
                         : "active; last warning: " + counters.last_warning());
    });
    log->info("active");
    const auto until = options.run_for_s > 0.0
                           ? Executor::Clock::now() +
                                 std::chrono::duration_cast<Executor::Clock::duration>(
                                     std::chrono::duration<double>(options.run_for_s))
                           : Executor::Clock::time_point::max();
    executor.Spin(KeepRunning(), until);

    node->Deactivate();
    status.Publish(StatusReporter::State::kFinalized, "stopped");
    const std::string summary = node->Summary();
    log->info("stopped: {}{}{} samples in, {} out, {} dropped", summary,
              summary.empty() ? "" : "; ", counters.in(), counters.out(), counters.dropped());
    node.reset();
  } catch (const InputError& e) {
    log->error("{}", e.what());
    node.reset();
    participant.reset();
    return kExitBadInput;
  } catch (const std::exception& e) {
    log->error("failed: {}", e.what());
    node.reset();
    participant.reset();
    return 1;
  }
  participant.reset();
  return 0;
}

}  // namespace stickrep::runtime
