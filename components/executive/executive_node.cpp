#include "executive/executive_node.h"

#include "basePubSubTypes.h"
#include "executive/executive_component.h"
#include "executive/executive_config.h"
#include "localizationPubSubTypes.h"
#include "missionPubSubTypes.h"
#include "runtime/component_node.h"
#include "stickrep/map_io.h"
#include "systemPubSubTypes.h"

namespace stickrep::executive {

namespace {

// The executive component on DDS: heartbeats whose liveliness is lost tell of a dead
// process; discovery tells why components may not have been heard.
class ExecutiveNode : public runtime::ComponentNode {
  std::unique_ptr<component::Component> Build(runtime::NodeContext& ctx,
                                              component::Context& cc) override {
    const ExecutiveConfig config = LoadExecutiveConfig(ctx.config);
    map_ = std::make_unique<map::Map>(map::LoadMap(ctx.system.map_file));
    runtime::Participant& participant = ctx.participant;
    const auto why_not_heard = [&participant]() -> std::string {
      const runtime::DiscoveryListener& d = participant.discovery();
      if (d.UsesServers() && d.ServersReached() == 0) {
        return "no discovery server reached at " + participant.servers_text();
      }
      return "";
    };
    auto executive = std::make_unique<ExecutiveComponent>(
        cc, *map_, config, ctx.host, why_not_heard,
        ExecutiveComponent::Outputs{
            Publish<msgs::MotionCommandPubSubType>("robot/motion/command"),
            Publish<msgs::MissionStatusPubSubType>("mission/status"),
            Publish<msgs::MissionGoalResultPubSubType>("mission/goal_result")});
    ExecutiveComponent* c = executive.get();
    Feed<msgs::OdometryPubSubType>("robot/odometry",
                                   [c](const message::Odometry& o) { c->OnOdometry(o); });
    Feed<msgs::ComponentStatusPubSubType>(
        "system/status", [c](const message::ComponentStatus& s) { c->OnHeartbeat(s); })
        .OnInstanceGone([c](const msgs::ComponentStatus& key) {
          c->OnHeartbeatGone(key.component_name());
        });
    Feed<msgs::LocalizationPosePubSubType>(
        "localization/pose", [c](const message::LocalizationPose& p) { c->OnPose(p); });
    Feed<msgs::MotionStatePubSubType>(
        "robot/motion/state", [c](const message::MotionState& m) { c->OnMotionState(m); });
    Feed<msgs::MissionGoalPubSubType>("mission/goal",
                                      [c](const message::MissionGoal& g) { c->OnGoal(g); });
    return executive;
  }

  std::unique_ptr<map::Map> map_;
};

}  // namespace

std::unique_ptr<runtime::ProcessNode> MakeExecutiveNode() {
  return std::make_unique<ExecutiveNode>();
}

}  // namespace stickrep::executive
