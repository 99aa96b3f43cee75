#include "executive/executive_node.h"

#include <fmt/format.h>

#include <map>

#include "basePubSubTypes.h"
#include "executive/mission.h"
#include "localizationPubSubTypes.h"
#include "missionPubSubTypes.h"
#include "runtime/endpoint.h"
#include "systemPubSubTypes.h"

namespace stickrep::executive {

namespace {

msgs::MissionState ToMsg(MissionState s) {
  switch (s) {
    case MissionState::kWaitingForComponents: return msgs::MISSION_WAITING_FOR_COMPONENTS;
    case MissionState::kRecoveringPose: return msgs::MISSION_RECOVERING_POSE;
    case MissionState::kLocalized: return msgs::MISSION_GOAL_REACHED;
    case MissionState::kStoppedFault: return msgs::MISSION_STOPPED_FAULT;
  }
  return msgs::MISSION_STOPPED_FAULT;
}

class ExecutiveNode : public runtime::ProcessNode {
 public:
  void Configure(runtime::NodeContext& ctx) override {
    ctx_ = &ctx;
    const StrictYaml& c = ctx.config;
    MissionConfig mission;
    for (const StrictYaml& name : c.Sequence("required_components")) {
      mission.required_components.push_back(name.As<std::string>());
    }
    mission.travel_speed_ftps = c.Get<double>("travel_speed_ftps", 0.1, 2.6, "ft/s");
    mission.travel_direction = c.Get<int>("travel_direction", -1, 1);
    if (mission.travel_direction == 0) c.Fail("travel_direction", "must be +1 or -1");
    const double command_rate_hz = c.Get<double>("command_rate_hz", 2.0, 100.0, "Hz");
    heartbeat_timeout_s_ = c.Get<double>("heartbeat_timeout_s", 0.5, 60.0, "s");
    exit_when_localized_ = c.Get<bool>("exit_when_localized");
    c.Finish();
    mission_ = std::make_unique<Mission>(mission);

    commands_ = std::make_unique<runtime::Writer<msgs::MotionCommandPubSubType>>(
        ctx.participant, "robot/motion/command");
    status_ = std::make_unique<runtime::Writer<msgs::MissionStatusPubSubType>>(ctx.participant,
                                                                              "mission/status");
    heartbeats_ = std::make_unique<runtime::Reader<msgs::ComponentStatusPubSubType>>(
        ctx.participant, ctx.executor, "system/status",
        [this](const msgs::ComponentStatus& s) { OnHeartbeat(s); });
    heartbeats_->OnInstanceGone([this](const msgs::ComponentStatus& key) {
      Gone(key.component_name(), "its status writer disappeared");
    });
    poses_ = std::make_unique<runtime::Reader<msgs::LocalizationPosePubSubType>>(
        ctx.participant, ctx.executor, "localization/pose",
        [this](const msgs::LocalizationPose& p) { OnPose(p); });
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
  void OnHeartbeat(const msgs::ComponentStatus& s) {
    ctx_->counters.CountIn();
    const std::string& name = s.component_name();
    if (s.state() == msgs::COMPONENT_FINALIZED) {
      Gone(name, "it stopped");
      return;
    }
    last_heartbeat_ns_[name] = ctx_->now_ns();
    if (s.state() == msgs::COMPONENT_ACTIVE) mission_->OnComponentActive(name);
    Report();
  }

  void Gone(const std::string& name, const std::string& why) {
    last_heartbeat_ns_.erase(name);
    mission_->OnComponentGone(name, why);
    Report();
  }

  void OnPose(const msgs::LocalizationPose& p) {
    ctx_->counters.CountIn();
    if (p.status() == msgs::LOCALIZATION_LOCALIZED) {
      mission_->OnLocalized(fmt::format("ring '{}' edge {} ({})", p.best().ring_id(),
                                        p.best().edge_index(),
                                        p.best().forward() ? "forward" : "backward"));
    } else if (p.status() == msgs::LOCALIZATION_LOST) {
      mission_->OnLost();
    }
    Report();
  }

  void OnGoal(const msgs::MissionGoal& g) {
    ctx_->counters.CountIn();
    PublishStatus(fmt::format("goal '{}' ({}) refused: goal execution is not built yet",
                              g.goal_id(), g.target()),
                  g.goal_id());
  }

  void Tick() {
    // A process whose heartbeat stopped without a goodbye has died.
    const int64_t now = ctx_->now_ns();
    std::vector<std::string> stale;
    for (const auto& [name, t] : last_heartbeat_ns_) {
      if (now - t > heartbeat_timeout_s_ * 1e9) stale.push_back(name);
    }
    for (const std::string& name : stale) {
      Gone(name, fmt::format("no heartbeat for {:.1f} s", heartbeat_timeout_s_));
    }
    const MotionRequest m = mission_->Motion();
    msgs::MotionCommand cmd;
    cmd.mode(m.move ? msgs::MOTION_VELOCITY : msgs::MOTION_STOP);
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

  void PublishStatus(const std::string& message, const std::string& goal_id = "") {
    msgs::MissionStatus s;
    s.state(ToMsg(mission_->state()));
    s.goal_id(goal_id);
    s.message(message.empty() ? mission_->last_message() : message);
    if (status_->Publish(s, ctx_->now_ns())) ctx_->counters.CountOut();
  }

  runtime::NodeContext* ctx_ = nullptr;
  std::unique_ptr<Mission> mission_;
  double heartbeat_timeout_s_ = 3.0;
  bool exit_when_localized_ = false;
  std::map<std::string, int64_t> last_heartbeat_ns_;
  std::unique_ptr<runtime::Writer<msgs::MotionCommandPubSubType>> commands_;
  std::unique_ptr<runtime::Writer<msgs::MissionStatusPubSubType>> status_;
  std::unique_ptr<runtime::Reader<msgs::ComponentStatusPubSubType>> heartbeats_;
  std::unique_ptr<runtime::Reader<msgs::LocalizationPosePubSubType>> poses_;
  std::unique_ptr<runtime::Reader<msgs::MissionGoalPubSubType>> goals_;
};

}  // namespace

std::unique_ptr<runtime::ProcessNode> MakeExecutiveNode() {
  return std::make_unique<ExecutiveNode>();
}

}  // namespace stickrep::executive
