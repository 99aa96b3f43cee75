#include "locomotion/locomotion_node.h"

#include "basePubSubTypes.h"
#include "locomotion/locomotion_component.h"
#include "locomotion/locomotion_config.h"
#include "runtime/component_node.h"
#include "sensing/robot_config.h"
#include "sensorsPubSubTypes.h"
#include "stickrep/map_io.h"

namespace stickrep::locomotion {

namespace {

// The locomotion component on DDS; the command stream's deadline (QoS) stops the base when
// the executive falls silent.
class LocomotionNode : public runtime::ComponentNode {
  std::unique_ptr<component::Component> Build(runtime::NodeContext& ctx,
                                              component::Context& cc) override {
    const sensing::RobotConfig robot = sensing::LoadRobotConfigFile(ctx.system.robot_file);
    // The floor's own hallway behaviour, where locomotion.yaml gives one (on_maps).
    const LocomotionConfig config = ForMap(LoadLocomotionConfig(ctx.config, robot),
                                           map::LoadMap(ctx.system.map_file).info().name);
    auto locomotion = std::make_unique<LocomotionComponent>(
        cc, config, robot.base.wheel_base_in,
        LocomotionComponent::Outputs{
            Publish<msgs::WheelCommandPubSubType>("device/base/wheel_command"),
            Publish<msgs::OdometryPubSubType>("robot/odometry"),
            Publish<msgs::MotionStatePubSubType>("robot/motion/state")});
    LocomotionComponent* c = locomotion.get();
    Feed<msgs::MotionCommandPubSubType>(
        "robot/motion/command", [c](const message::MotionCommand& m) { c->OnCommand(m); })
        .OnDeadlineMissed([c] { c->OnCommandsSilent(); });
    Feed<msgs::EncoderReadingPubSubType>(
        "device/base/encoders", [c](const message::EncoderReading& e) { c->OnEncoders(e); });
    Feed<msgs::SonarScanPubSubType>("robot/sonar",
                                    [c](const message::SonarScan& s) { c->OnScan(s); });
    return locomotion;
  }
};

}  // namespace

std::unique_ptr<runtime::ProcessNode> MakeLocomotionNode() {
  return std::make_unique<LocomotionNode>();
}

}  // namespace stickrep::locomotion
