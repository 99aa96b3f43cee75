#include "executive/executive_node.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <map>
#include <optional>

#include "basePubSubTypes.h"
#include "executive/executive.h"
#include "executive/executive_config.h"
#include "executive/link_monitor.h"
#include "executive/mission.h"
#include "executive/route.h"
#include "stickrep/map_io.h"
#include "localizationPubSubTypes.h"
#include "missionPubSubTypes.h"
#include "runtime/endpoint.h"
#include "systemPubSubTypes.h"

namespace stickrep::executive {

namespace {

msgs::MissionState ToMsg(MissionState s) {
  switch (s) {
    case MissionState::kWaitingForComponents: return msgs::MISSION_WAITING_FOR_COMPONENTS;
    case MissionState::kAligning: return msgs::MISSION_ALIGNING;
    case MissionState::kRecoveringPose: return msgs::MISSION_RECOVERING_POSE;
    case MissionState::kLocalized: return msgs::MISSION_LOCALIZED;
    case MissionState::kExecutingGoal: return msgs::MISSION_EXECUTING_GOAL;
    case MissionState::kGoalReached: return msgs::MISSION_GOAL_REACHED;
    case MissionState::kStoppedFault: return msgs::MISSION_STOPPED_FAULT;
    case MissionState::kLinkLost: return msgs::MISSION_LINK_LOST;
  }
  return msgs::MISSION_STOPPED_FAULT;
}

class ExecutiveNode : public runtime::ProcessNode {
 public:
  void Configure(runtime::NodeContext& ctx) override {
    ctx_ = &ctx;
    const ExecutiveConfig config = LoadExecutiveConfig(ctx.config);
    const MissionConfig& mission = config.mission;
    const double command_rate_hz = config.command_rate_hz;
    links_ = std::make_unique<LinkMonitor>(ctx.host, config.heartbeat_timeout_s,
                                           config.link_settle_s);
    exit_when_localized_ = config.exit_when_localized;
    map_ = std::make_unique<map::Map>(map::LoadMap(ctx.system.map_file));
    executive_ = std::make_unique<Executive>(*map_, mission);
    mission_ = &executive_->mission();
    odometry_ = std::make_unique<runtime::Reader<msgs::OdometryPubSubType>>(
        ctx.participant, ctx.executor, "robot/odometry", [this](const msgs::Odometry& o) {
          ctx_->counters.CountIn();
          if (!std::isfinite(o.distance_in())) {
            ctx_->counters.Drop("robot/odometry", "non-finite distance");
            return;
          }
          executive_->OnOdometer(o.distance_in());
          Report();
        });

    commands_ = std::make_unique<runtime::Writer<msgs::MotionCommandPubSubType>>(
        ctx.participant, "robot/motion/command");
    results_ = std::make_unique<runtime::Writer<msgs::MissionGoalResultPubSubType>>(
        ctx.participant, "mission/goal_result");
    status_ = std::make_unique<runtime::Writer<msgs::MissionStatusPubSubType>>(ctx.participant,
                                                                              "mission/status");
    heartbeats_ = std::make_unique<runtime::Reader<msgs::ComponentStatusPubSubType>>(
        ctx.participant, ctx.executor, "system/status",
        [this](const msgs::ComponentStatus& s) { OnHeartbeat(s); });
    heartbeats_->OnInstanceGone([this](const msgs::ComponentStatus& key) {
      links_->OnSilent(key.component_name(), "its heartbeat's liveliness was lost", NowS());
    });
    poses_ = std::make_unique<runtime::Reader<msgs::LocalizationPosePubSubType>>(
        ctx.participant, ctx.executor, "localization/pose",
        [this](const msgs::LocalizationPose& p) { OnPose(p); });
    motion_ = std::make_unique<runtime::Reader<msgs::MotionStatePubSubType>>(
        ctx.participant, ctx.executor, "robot/motion/state", [this](const msgs::MotionState& m) {
          ctx_->counters.CountIn();
          mission_->OnMotionState(m.in_envelope(), m.header().stamp_ns() * 1e-9);
          Report();
        });
    goals_ = std::make_unique<runtime::Reader<msgs::MissionGoalPubSubType>>(
        ctx.participant, ctx.executor, "mission/goal",
        [this](const msgs::MissionGoal& g) { OnGoal(g); });
    ctx.executor.AddTimer(1.0 / command_rate_hz, [this] { Tick(); });
    ctx.executor.AddTimer(1.0, [this] { PublishStatus(""); });
  }

  void Deactivate() override {
    msgs::MotionCommand stop;
    stop.mode(msgs::MOTION_STOP);
    commands_->Publish(stop, ctx_->now_ns());
  }

  std::string Summary() const override {
    return fmt::format("mission {}: {}", ToString(mission_->state()), mission_->last_message());
  }

 private:
  double NowS() const { return ctx_->now_ns() * 1e-9; }

  void OnHeartbeat(const msgs::ComponentStatus& s) {
    ctx_->counters.CountIn();
    const std::string& name = s.component_name();
    if (s.state() == msgs::COMPONENT_FINALIZED) {
      Handle(links_->OnStopped(name));
      return;
    }
    Handle(links_->OnHeartbeat(name, s.host(), NowS()));
    if (s.state() == msgs::COMPONENT_ACTIVE && !links_->HostLost(s.host())) {
      mission_->OnComponentActive(name);
    }
    Report();
  }

  // What the link monitor concluded: a dead process stops the mission; a silent host stops
  // the robot until it is heard again.
  void Handle(const std::vector<LinkMonitor::Event>& events) {
    for (const LinkMonitor::Event& e : events) {
      switch (e.kind) {
        case LinkMonitor::Event::Kind::kProcessGone:
          mission_->OnComponentGone(e.processes.front(), e.why);
          break;
        case LinkMonitor::Event::Kind::kHostLost:
          ctx_->log->warn("{}: {}", e.why, fmt::join(e.processes, ", "));
          mission_->OnLinkLost(e.host, e.why);
          break;
        case LinkMonitor::Event::Kind::kHostBack:
          ctx_->log->info("{}: {}", e.why, fmt::join(e.processes, ", "));
          mission_->OnLinkBack(e.host, e.outage_s, localized_);
          for (const std::string& name : e.processes) mission_->OnComponentActive(name);
          break;
      }
    }
    Report();
  }

  void OnPose(const msgs::LocalizationPose& p) {
    ctx_->counters.CountIn();
    localized_ = p.status() == msgs::LOCALIZATION_LOCALIZED;
    if (p.status() == msgs::LOCALIZATION_LOCALIZED) {
      const int ring = map_->FindRing(p.best().ring_id());
      if (ring < 0) {
        ctx_->counters.Drop("localization/pose", "a ring that is not on the map");
        return;
      }
      executive_->OnLocalized(MapPose{ring, static_cast<int>(p.best().edge_index()),
                                      p.best().forward() ? +1 : -1, p.best().offset_in()},
                              fmt::format("ring '{}' edge {} ({})", p.best().ring_id(),
                                          p.best().edge_index(),
                                          p.best().forward() ? "forward" : "backward"));
    } else if (p.status() == msgs::LOCALIZATION_LOST) {
      executive_->OnLost();
    }
    Report();
  }

  void OnGoal(const msgs::MissionGoal& g) {
    ctx_->counters.CountIn();
    msgs::MissionGoalResult result;
    result.goal_id(g.goal_id());
    result.target(g.target());
    if (const auto why = executive_->OnGoal(g.goal_id(), g.target())) {
      ctx_->log->warn("goal '{}' ({}) refused: {}", g.goal_id(), g.target(), *why);
      PublishStatus(fmt::format("goal '{}' ({}) refused: {}", g.goal_id(), g.target(), *why),
                    g.goal_id());
      result.accepted(false);
      result.reason(*why);
    } else {
      result.accepted(true);
      result.reason(mission_->last_message());
    }
    if (results_->Publish(result, ctx_->now_ns())) ctx_->counters.CountOut();
    Report();
  }

  void Tick() {
    const int64_t now = ctx_->now_ns();
    Handle(links_->Tick(now * 1e-9));
    const MotionRequest m = mission_->Motion();
    msgs::MotionCommand cmd;
    cmd.mode(m.move ? msgs::MOTION_FOLLOW_HALLWAY : msgs::MOTION_STOP);
    cmd.linear_speed_ftps(m.linear_speed_ftps);
    if (commands_->Publish(cmd, now)) ctx_->counters.CountOut();
  }

  void Report() {
    for (const std::string& t : mission_->TakeTransitions()) {
      ctx_->log->info("mission: {}", t);
      PublishStatus("");
      if (exit_when_localized_ && mission_->state() == MissionState::kLocalized) {
        ctx_->log->info("mission complete: stopping");
        ctx_->request_stop();
      }
    }
  }

  // While waiting: which processes, and whether discovery could find them at all.
  std::string WaitingMessage() const {
    std::string why = fmt::format("waiting for {}: not heard yet", fmt::join(mission_->Missing(), ", "));
    const runtime::DiscoveryListener& d = ctx_->participant.discovery();
    if (d.UsesServers() && d.ServersReached() == 0) {
      why += "; no discovery server reached at " + ctx_->participant.servers_text();
    }
    return why;
  }

  void PublishStatus(const std::string& message, const std::string& goal_id = "") {
    msgs::MissionStatus s;
    s.state(ToMsg(mission_->state()));
    s.goal_id(goal_id);
    std::string text = message.empty() ? mission_->last_message() : message;
    if (message.empty() && mission_->state() == MissionState::kWaitingForComponents) {
      text = WaitingMessage();
      if (++waiting_reports_ % 10 == 5) ctx_->log->warn("{}", text);
    }
    s.message(text);
    if (status_->Publish(s, ctx_->now_ns())) ctx_->counters.CountOut();
  }

  runtime::NodeContext* ctx_ = nullptr;
  std::unique_ptr<map::Map> map_;
  std::unique_ptr<Executive> executive_;
  Mission* mission_ = nullptr;  // executive_'s
  std::unique_ptr<runtime::Reader<msgs::OdometryPubSubType>> odometry_;
  std::unique_ptr<LinkMonitor> links_;
  bool localized_ = false;  // the localizer's latest status
  int waiting_reports_ = 0;
  bool exit_when_localized_ = false;
  std::unique_ptr<runtime::Writer<msgs::MotionCommandPubSubType>> commands_;
  std::unique_ptr<runtime::Writer<msgs::MissionStatusPubSubType>> status_;
  std::unique_ptr<runtime::Writer<msgs::MissionGoalResultPubSubType>> results_;
  std::unique_ptr<runtime::Reader<msgs::ComponentStatusPubSubType>> heartbeats_;
  std::unique_ptr<runtime::Reader<msgs::LocalizationPosePubSubType>> poses_;
  std::unique_ptr<runtime::Reader<msgs::MissionGoalPubSubType>> goals_;
  std::unique_ptr<runtime::Reader<msgs::MotionStatePubSubType>> motion_;
};

}  // namespace

std::unique_ptr<runtime::ProcessNode> MakeExecutiveNode() {
  return std::make_unique<ExecutiveNode>();
}

}  // namespace stickrep::executive
