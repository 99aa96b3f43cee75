#pragma once

#include <cstddef>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "runtime/deployment_options.h"
#include "runtime/discovery.h"
#include "runtime/participant.h"
#include "runtime/system_config.h"

namespace stickrep::console {

// Options shared by the console's commands.
struct ConsoleOptions {
  std::string system_file;
  int domain_id = -1;          // -1: from the system file
  // How long `list`, `info`, `doctor`, `bw` listen to discovery. Fast DDS's simple discovery
  // announces a participant every 3 s: a new console may hear a running process only then.
  double wait_s = 4.0;
  int count = 0;               // `echo`: stop after this many samples (0: until stopped)
  double timeout_s = 0.0;      // `echo`: give up after this long (0: never)
  bool json = false;
  std::string field;           // `echo --field a.b`: print only that member
  std::size_t window = 50;     // `hz`, `delay`: samples in the sliding window
  double duration_s = 0.0;     // `hz`, `delay`: stop after this long (0: until Ctrl-C)
  int cols = 100;              // `pose`: width of the map drawn in characters
  std::string png;             // `pose --png`: write the map with the pose to this file
  // Fast DDS profile and discovery servers; the console joins a discovery-server deployment
  // as a super client (deploy/fastdds/discovery_client.xml) so that it sees every topic.
  runtime::DeploymentOptions deployment;
};

// A participant of a base-station tool on a deployment's domain (the console, the recorder,
// the replayer).
struct DomainSession {
  runtime::SystemConfig system;
  std::unique_ptr<runtime::Participant> participant;
  const runtime::DiscoveryListener* listener = nullptr;
};

// Joins the domain of `system_file` (or `domain_id` when >= 0) as `name`; through a
// discovery server, waits (at most max(5 s, wait_s)) until one is reached and says so on
// stderr when none is. Throws InputError for bad settings.
// `shared_memory` false: UDP only, whatever the system file says
// (runtime::ParticipantConfig::shared_memory).
DomainSession JoinDomain(const std::string& system_file, int domain_id,
                         const runtime::DeploymentOptions& deployment, const std::string& name,
                         double wait_s, double announcement_period_s = 0.0,
                         bool shared_memory = true);

// Joins as "stickrep-console", over UDP only: a console stopped or slow on the robot's own
// computer must not hold up the robot's writers through a full shared-memory port.
DomainSession JoinAsConsole(const ConsoleOptions& o);

// `list`: every topic seen on the domain with its type, writer and reader counts and QoS.
// Returns the process exit code.
int ListTopics(const ConsoleOptions& options, std::ostream& out);

// `echo TOPIC`: one JSON line per sample until the count, the timeout or a signal.
int EchoTopic(const ConsoleOptions& options, const std::string& topic, std::ostream& out);

// `hz TOPIC` / `delay TOPIC`: every second, the rate with the min, max and standard
// deviation of the period, or the delay from the writer's source timestamp to reception,
// over the last `window` samples. 1 when no writer or no sample comes within timeout_s.
enum class TopicStat { kRate, kDelay };
int WatchTopic(const ConsoleOptions& options, const std::string& topic, TopicStat stat,
               std::ostream& out);

// `info TOPIC`: every writer and reader of the topic with its process, host (from the
// processes' heartbeats) and QoS; `verbose` adds GUIDs and types.
int InfoTopic(const ConsoleOptions& options, const std::string& topic, bool verbose,
              std::ostream& out);

// `status`: one line per process from system/status (host, state, heartbeat age, samples
// in/out/dropped, last warning), again every wait_s (at least 1 s) until Ctrl-C or
// duration_s; once with count 1. 1 when no heartbeat comes within timeout_s.
int ShowStatus(const ConsoleOptions& options, std::ostream& out);

// `doctor`: requested/offered QoS that do not match, type names that differ, readers without
// writers and writers without readers (console/doctor.h), each naming the topic, both
// endpoints and the policy. 1 when some pair cannot match or nothing is on the domain.
int Doctor(const ConsoleOptions& options, std::ostream& out);

// `bw`: every topic that has a writer, subscribed for timeout_s (default 10 s) after
// listening to discovery for wait_s: samples, rate, mean serialized size and bytes/s.
int MeasureBandwidth(const ConsoleOptions& options, std::ostream& out);

// `goal TARGET`: sends a goal (a door or node of the map, executive/route.h) on
// mission/goal and waits up to timeout_s (default 10 s) for the executive's answer on
// mission/goal_result (goal id, accepted or refused, the reason); prints it (JSON with
// json). 0 when the goal was accepted, 1 when refused or unanswered.
int SendGoal(const ConsoleOptions& options, const std::string& goal_id, const std::string& target,
             std::ostream& out);

// `pose`: the localizer's map (map/stickrep) drawn in the terminal with the best pose as an
// arrow and the other hypotheses as digits (console/pose_view.h), under a line of status,
// confidence, candidates and the best pose; again every second until Ctrl-C or duration_s,
// once with count 1. json prints the pose as one JSON object per refresh instead (the map
// is then not needed); png writes one picture of the map to scale with the pose and exits.
// 1 when the map or a pose does not come within timeout_s (default 10 s); InputError for a
// png path that cannot be written.
int ShowPose(const ConsoleOptions& options, std::ostream& out);

// The table `list` prints, from summaries (kept apart from DDS for testing).
void PrintTopicTable(const std::vector<runtime::TopicSummary>& topics, std::ostream& out);

}  // namespace stickrep::console
