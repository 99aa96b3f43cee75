#include "runtime/deployment_options.h"

#include <fmt/format.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <string>
#include <vector>

namespace stickrep::runtime {

void AddDeploymentOptions(CLI::App& app, DeploymentOptions& o) {
  app.add_option("--fastdds-profile", o.profile_xml,
                 "Fast DDS XML profile file (transports, discovery), over the system file's");
  app.add_option("--fastdds-profile-name", o.profile_name,
                 "participant profile in that file (default: the file's default profile)");
  app.add_option("--discovery-server", o.discovery_servers,
                 "discovery server addresses IP:PORT[,IP:PORT] (the i-th is server id i); "
                 "makes this process a discovery-server client");
  app.add_option("--host", o.host, "label of the host this process runs on, sent in its "
                                   "heartbeat (default: the host name)");
  app.add_option("--security-dir", o.security_dir,
                 "DDS Security: authenticate, check permissions and encrypt with the "
                 "identities, governance and permissions of this directory "
                 "(deploy/security/make-keys.sh makes it)");
  app.add_option("--security-identity", o.security_identity,
                 "the identity of the security directory this participant is (default: "
                 "the process's name, e.g. executive)");
}

ParticipantConfig MakeParticipantConfig(const SystemConfig& system, const DeploymentOptions& o,
                                        const std::string& participant_name) {
  ParticipantConfig c{system.domain_id, participant_name, system.fastdds_profile_xml,
                      system.fastdds_profile_name, {}};
  if (!o.profile_xml.empty()) {
    c.profile_xml = o.profile_xml;
    c.profile_name = o.profile_name;
  } else if (!o.profile_name.empty()) {
    c.profile_name = o.profile_name;
  }
  c.discovery_servers = SplitServerList(o.discovery_servers);
  c.shared_memory = system.shared_memory;
  if (!o.security_dir.empty()) {
    const std::string prefix = "stickrep-";
    std::string identity = o.security_identity;
    if (identity.empty()) {
      identity = participant_name.rfind(prefix, 0) == 0 ? participant_name.substr(prefix.size())
                                                        : participant_name;
    }
    c.security = SecurityConfig{o.security_dir, identity};
  }
  return c;
}

std::string HostLabel(const DeploymentOptions& o) {
  if (!o.host.empty()) return o.host;
  char name[256] = {};
  if (gethostname(name, sizeof(name) - 1) != 0) return "?";
  return name;
}

std::vector<std::string> SplitServerList(const std::string& text) {
  std::vector<std::string> out;
  std::string current;
  for (const char ch : text + ",") {
    if (ch == ',' || ch == ';') {
      if (!current.empty()) out.push_back(current);
      current.clear();
    } else if (ch != ' ') {
      current += ch;
    }
  }
  return out;
}

namespace {
constexpr int kTicksToWaitForAName = 5;
}  // namespace

void WatchAuthentication(const Participant& participant, Executor& executor,
                         std::shared_ptr<spdlog::logger> log) {
  struct Logged {
    size_t refused = 0;
    size_t authenticated = 0;
    int waited_for_name = 0;  // timer ticks the next authenticated participant had no name
    std::vector<std::string> unnamed;  // logged without a name: logged again with it
  };
  auto logged = std::make_shared<Logged>();
  executor.AddTimer(1.0, [&participant, log, logged] {
    const DiscoveryListener& d = participant.discovery();
    const auto refused = d.Refused();
    for (; logged->refused < refused.size(); ++logged->refused) {
      log->warn("DDS Security: participant {} failed authentication: ignored",
                refused[logged->refused]);
    }
    // The launcher's handshake watch reads the names from these lines: a participant whose
    // name came after it was logged is logged again, named.
    auto& unnamed = logged->unnamed;
    for (auto it = unnamed.begin(); it != unnamed.end();) {
      const std::string name = d.NameOf(*it);
      if (name.empty()) {
        ++it;
        continue;
      }
      log->info("DDS Security: participant {} ({}) authenticated", *it, name);
      it = unnamed.erase(it);
    }
    const auto authenticated = d.AuthenticatedPrefixes();
    for (; logged->authenticated < authenticated.size(); ++logged->authenticated) {
      const std::string& prefix = authenticated[logged->authenticated];
      const std::string name = d.NameOf(prefix);
      // The name comes with the participant's discovery, just after its authentication: wait
      // a few ticks for it, then log it without and again once it comes.
      if (name.empty() && ++logged->waited_for_name < kTicksToWaitForAName) break;
      logged->waited_for_name = 0;
      if (name.empty()) unnamed.push_back(prefix);
      log->info("DDS Security: participant {} ({}) authenticated", prefix,
                name.empty() ? "name not yet discovered" : name);
    }
  });
}

void WatchDiscoveryServers(const Participant& participant, Executor& executor,
                           std::shared_ptr<spdlog::logger> log, double warn_period_s) {
  if (!participant.discovery().UsesServers()) return;
  struct State {
    int reached = 0;
    std::chrono::steady_clock::time_point since = std::chrono::steady_clock::now();
    double next_warn_s = 5.0;
  };
  auto state = std::make_shared<State>();
  log->info("discovery through the server(s) at {}", participant.servers_text());
  executor.AddTimer(1.0, [&participant, log, state, warn_period_s] {
    const int reached = participant.discovery().ServersReached();
    const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                                        state->since).count();
    if (reached > 0 && state->reached == 0) {
      log->info("discovery server reached ({} of them) after {:.1f} s", reached, waited);
    } else if (reached == 0 && state->reached > 0) {
      log->warn("discovery server at {} lost: peers already discovered keep talking; "
                "retrying", participant.servers_text());
      state->since = std::chrono::steady_clock::now();
      state->next_warn_s = 5.0;
    } else if (reached == 0 && waited >= state->next_warn_s) {
      log->warn("no discovery server reached at {} for {:.0f} s: processes on other hosts "
                "cannot be found yet; retrying", participant.servers_text(), waited);
      state->next_warn_s += warn_period_s;
    }
    state->reached = reached;
  });
}

}  // namespace stickrep::runtime
