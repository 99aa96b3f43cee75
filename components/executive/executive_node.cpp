#include "executive/executive_node.h"

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <optional>

#include "basePubSubTypes.h"
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
    case MissionState::kRecoveringPose: return msgs::MISSION_RECOVERING_POSE;
    case MissionState::kLocalized: return msgs::MISSION_LOCALIZED;
    case MissionState::kExecutingGoal: return msgs::MISSION_EXECUTING_GOAL;
    case MissionState::kGoalReached: return msgs::MISSION_GOAL_REACHED;
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
    travel_direction_ = mission.travel_direction;
    map_ = std::make_unique<map::Map>(map::LoadMap(ctx.system.map_file));
    planner_ = std::make_unique<RoutePlanner>(*map_);
    odometry_ = std::make_unique<runtime::Reader<msgs::OdometryPubSubType>>(
        ctx.participant, ctx.executor, "robot/odometry", [this](const msgs::Odometry& o) {
          ctx_->counters.CountIn();
          if (!std::isfinite(o.distance_in())) {
            ctx_->counters.Drop("robot/odometry", "non-finite distance");
            return;
          }
          odometer_in_ = o.distance_in();
          mission_->OnOdometer(odometer_in_);
          Report();
        });

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
      const int ring = map_->FindRing(p.best().ring_id());
      if (ring >= 0) {
        pose_ = MapPose{ring, static_cast<int>(p.best().edge_index()),
                        p.best().forward() ? +1 : -1, p.best().offset_in()};
      }
      mission_->OnLocalized(fmt::format("ring '{}' edge {} ({})", p.best().ring_id(),
                                        p.best().edge_index(),
                                        p.best().forward() ? "forward" : "backward"));
    } else if (p.status() == msgs::LOCALIZATION_LOST) {
      pose_.reset();
      mission_->OnLost();
    }
    Report();
  }

  void OnGoal(const msgs::MissionGoal& g) {
    ctx_->counters.CountIn();
    const auto refuse = [&](const std::string& why) {
      ctx_->log->warn("goal '{}' ({}) refused: {}", g.goal_id(), g.target(), why);
      PublishStatus(fmt::format("goal '{}' ({}) refused: {}", g.goal_id(), g.target(), why),
                    g.goal_id());
    };
    if (const auto why = mission_->CanTakeGoal()) return refuse(*why);
    if (!pose_) return refuse("the pose is not known yet");
    const RouteResult route = planner_->Plan(*pose_, g.target());
    if (!route) return refuse(route.error);
    if (!route.route->crossings.empty()) {
      return refuse("the route crosses into another hallway, and turning at a join is not "
                    "built yet");
    }
    // Keep going means the direction the base travelled while localizing.
    const int sign = route.route->initial_travel_sign >= 0 ? travel_direction_ : -travel_direction_;
    mission_->StartGoal(GoalPlan{g.goal_id(), planner_->Describe(*route.route), sign,
                                 route.route->distance_in},
                        odometer_in_);
    Report();
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
  std::unique_ptr<map::Map> map_;
  std::unique_ptr<RoutePlanner> planner_;
  std::optional<MapPose> pose_;
  double odometer_in_ = 0.0;
  int travel_direction_ = 1;
  std::unique_ptr<runtime::Reader<msgs::OdometryPubSubType>> odometry_;
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
