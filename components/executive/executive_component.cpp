#include "executive/executive_component.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>

namespace stickrep::executive {

namespace {

message::MissionState ToMessage(MissionState s) {
  switch (s) {
    case MissionState::kWaitingForComponents: return message::MissionState::kWaitingForComponents;
    case MissionState::kAligning: return message::MissionState::kAligning;
    case MissionState::kRecoveringPose: return message::MissionState::kRecoveringPose;
    case MissionState::kLocalized: return message::MissionState::kLocalized;
    case MissionState::kExecutingGoal: return message::MissionState::kExecutingGoal;
    case MissionState::kGoalReached: return message::MissionState::kGoalReached;
    case MissionState::kStoppedFault: return message::MissionState::kStoppedFault;
    case MissionState::kLinkLost: return message::MissionState::kLinkLost;
  }
  return message::MissionState::kStoppedFault;
}

}  // namespace

ExecutiveComponent::ExecutiveComponent(component::Context& ctx, const map::Map& map,
                                       const ExecutiveConfig& config, const std::string& host,
                                       std::function<std::string()> why_not_heard, Outputs out)
    : ctx_(ctx),
      map_(map),
      executive_(map, config.mission),
      mission_(executive_.mission()),
      links_(host, config.heartbeat_timeout_s, config.link_settle_s),
      command_rate_hz_(config.command_rate_hz),
      exit_when_localized_(config.exit_when_localized),
      why_not_heard_(std::move(why_not_heard)),
      out_(out) {}

std::vector<component::Timer> ExecutiveComponent::Timers() {
  return {{1.0 / command_rate_hz_, [this] { Tick(); }}, {1.0, [this] { PublishStatus(""); }}};
}

void ExecutiveComponent::Deactivate() {
  message::MotionCommand stop;
  stop.header.stamp_ns = ctx_.NowNs();
  stop.mode = message::MotionMode::kStop;
  out_.commands.Publish(stop);
}

std::string ExecutiveComponent::Summary() const {
  return fmt::format("mission {}: {}", ToString(mission_.state()), mission_.last_message());
}

void ExecutiveComponent::OnOdometry(const message::Odometry& o) {
  executive_.OnOdometer(o.distance_in);
  mission_.OnBaseSpeed(o.linear_speed_ftps, o.header.stamp_ns * 1e-9);
  Report();
}

void ExecutiveComponent::OnMotionState(const message::MotionState& m) {
  mission_.OnMotionState(m.in_envelope, m.header.stamp_ns * 1e-9);
  Report();
}

void ExecutiveComponent::OnHeartbeat(const message::ComponentStatus& s) {
  const std::string& name = s.component_name;
  // A process restarted faster than its death was noticed: its new heartbeat writer counts
  // from 1 again. It was absent meanwhile (and a new localizer has no pose).
  const auto last = heartbeat_sequence_.find(name);
  if (last != heartbeat_sequence_.end() && s.header.sequence < last->second) {
    ctx_.log->warn("process '{}' restarted (its heartbeats count from {} again)", name,
                   s.header.sequence);
    mission_.OnComponentGone(name, "it restarted");
  }
  heartbeat_sequence_[name] = s.header.sequence;
  if (s.state == message::ComponentState::kFinalized) {
    Handle(links_.OnStopped(name));
    return;
  }
  Handle(links_.OnHeartbeat(name, s.host, NowS()));
  if (s.state == message::ComponentState::kActive && !links_.HostLost(s.host)) {
    if (mission_.Absent().count(name) > 0) {
      ctx_.log->info("process '{}' is back, active on host '{}'", name, s.host);
    }
    mission_.OnComponentActive(name);
  }
  Report();
}

void ExecutiveComponent::OnHeartbeatGone(const std::string& component_name) {
  links_.OnSilent(component_name, "its heartbeat's liveliness was lost", NowS());
}

// What the link monitor concluded: a dead process stops the robot until it is back; a silent
// host stops the robot until it is heard again.
void ExecutiveComponent::Handle(const std::vector<LinkMonitor::Event>& events) {
  for (const LinkMonitor::Event& e : events) {
    switch (e.kind) {
      case LinkMonitor::Event::Kind::kProcessGone:
        mission_.OnComponentGone(e.processes.front(), e.why);
        break;
      case LinkMonitor::Event::Kind::kHostLost:
        ctx_.log->warn("{}: {}", e.why, fmt::join(e.processes, ", "));
        mission_.OnLinkLost(e.host, e.why);
        break;
      case LinkMonitor::Event::Kind::kHostBack:
        ctx_.log->info("{}: {}", e.why, fmt::join(e.processes, ", "));
        mission_.OnLinkBack(e.host, e.outage_s, localized_);
        for (const std::string& name : e.processes) mission_.OnComponentActive(name);
        break;
    }
  }
  Report();
}

void ExecutiveComponent::OnPose(const message::LocalizationPose& p) {
  localized_ = p.status == message::LocalizationStatus::kLocalized;
  if (p.status == message::LocalizationStatus::kLocalized) {
    const int ring = map_.FindRing(p.best.ring_id);
    if (ring < 0) {
      ctx_.counters.Drop("localization/pose", "a ring that is not on the map");
      return;
    }
    executive_.OnLocalized(
        MapPose{ring, p.best.edge_index, p.best.forward ? +1 : -1, p.best.offset_in},
        fmt::format("ring '{}' edge {} ({})", p.best.ring_id, p.best.edge_index,
                    p.best.forward ? "forward" : "backward"));
  } else {
    // LOST (the evidence is against the pose) or RECOVERING (not sure of it any more): the
    // pose is no longer to be trusted either way.
    executive_.OnLost();
  }
  Report();
}

void ExecutiveComponent::OnGoal(const message::MissionGoal& g) {
  message::MissionGoalResult result;
  result.header.stamp_ns = ctx_.NowNs();
  result.goal_id = g.goal_id;
  result.target = g.target;
  if (const auto why = executive_.OnGoal(g.goal_id, g.target)) {
    ctx_.log->warn("goal '{}' ({}) refused: {}", g.goal_id, g.target, *why);
    PublishStatus(fmt::format("goal '{}' ({}) refused: {}", g.goal_id, g.target, *why),
                  g.goal_id);
    result.accepted = false;
    result.reason = *why;
  } else {
    result.accepted = true;
    result.reason = mission_.last_message();
  }
  out_.results.Publish(result);
  Report();
}

void ExecutiveComponent::Tick() {
  Handle(links_.Tick(NowS()));
  const MotionRequest m = mission_.Motion();
  message::MotionCommand cmd;
  cmd.header.stamp_ns = ctx_.NowNs();
  cmd.mode = m.move ? message::MotionMode::kFollowHallway : message::MotionMode::kStop;
  cmd.linear_speed_ftps = m.linear_speed_ftps;
  out_.commands.Publish(cmd);
}

void ExecutiveComponent::Report() {
  for (const std::string& t : mission_.TakeTransitions()) {
    ctx_.log->info("mission: {}", t);
    PublishStatus("");
    if (exit_when_localized_ && mission_.state() == MissionState::kLocalized) {
      ctx_.log->info("mission complete: stopping");
      ctx_.request_stop();
    }
  }
}

// While waiting: which processes, and what the transport can say about them.
std::string ExecutiveComponent::WaitingMessage() const {
  std::string why =
      fmt::format("waiting for {}: not heard yet", fmt::join(mission_.Missing(), ", "));
  const std::string transport = why_not_heard_ ? why_not_heard_() : "";
  if (!transport.empty()) why += "; " + transport;
  return why;
}

void ExecutiveComponent::PublishStatus(const std::string& text, const std::string& goal_id) {
  message::MissionStatus s;
  s.header.stamp_ns = ctx_.NowNs();
  s.state = ToMessage(mission_.state());
  s.goal_id = goal_id;
  s.message = text.empty() ? mission_.last_message() : text;
  if (text.empty() && mission_.state() == MissionState::kWaitingForComponents) {
    s.message = WaitingMessage();
    if (++waiting_reports_ % 10 == 5) ctx_.log->warn("{}", s.message);
  }
  out_.status.Publish(s);
}

}  // namespace stickrep::executive
