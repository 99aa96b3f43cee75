#pragma once

#include <spdlog/logger.h>

#include <memory>
#include <string>
#include <vector>

#include "runtime/executor.h"
#include "runtime/participant.h"
#include "runtime/system_config.h"

namespace CLI {
class App;
}

namespace stickrep::runtime {

// How a process joins a deployment that spans hosts, from its command line: a Fast DDS XML
// profile (transports, discovery) and the discovery servers' addresses, over what the
// system file says, and the label of the host it runs on. deploy/*.launch.yaml pass them.
struct DeploymentOptions {
  std::string profile_xml;        // --fastdds-profile
  std::string profile_name;       // --fastdds-profile-name
  std::string discovery_servers;  // --discovery-server "IP:PORT[,IP:PORT]"
  std::string host;               // --host (default: the machine's host name)
  std::string security_dir;       // --security-dir: DDS Security from this directory
  std::string security_identity;  // --security-identity (default: the process's name)
};

void AddDeploymentOptions(CLI::App& app, DeploymentOptions& options);

// The participant settings of a process named `participant_name`: the command line's
// profile and servers where given, else the system file's. Secured (--security-dir), the
// participant is the identity --security-identity, else its name without "stickrep-"
// ("stickrep-executive" is identity "executive").
ParticipantConfig MakeParticipantConfig(const SystemConfig& system,
                                        const DeploymentOptions& options,
                                        const std::string& participant_name);

// --host, or the machine's host name.
std::string HostLabel(const DeploymentOptions& options);

// "10.0.0.1:11811, 10.0.0.2:11811" -> {"10.0.0.1:11811", "10.0.0.2:11811"} (commas or
// semicolons between addresses).
std::vector<std::string> SplitServerList(const std::string& text);

// For a discovery-server client: says when the servers are reached and lost, and warns
// every `warn_period_s` while none is reached (the process keeps running and retrying).
void WatchDiscoveryServers(const Participant& participant, Executor& executor,
                           std::shared_ptr<spdlog::logger> log, double warn_period_s = 10.0);

// For a secured participant: logs each remote participant whose authentication failed (an
// outsider, or a peer with a certificate of another CA), checked every second.
void WatchAuthentication(const Participant& participant, Executor& executor,
                         std::shared_ptr<spdlog::logger> log);

}  // namespace stickrep::runtime
