#include "sonar/sonar_node.h"

#include "runtime/component_node.h"
#include "sensing/robot_config.h"
#include "sensorsPubSubTypes.h"
#include "sonar/sonar_component.h"

namespace stickrep::sonar {

namespace {

class SonarNode : public runtime::ComponentNode {
  std::unique_ptr<component::Component> Build(runtime::NodeContext& ctx,
                                              component::Context& cc) override {
    const std::string device = ctx.config.Get<std::string>("device");
    if (device == "serial") {
      ctx.config.Fail("device", "the serial sonar driver is not built yet; use 'virtual'");
    } else if (device != "virtual") {
      ctx.config.Fail("device", "'" + device + "' is not one of: virtual, serial");
    }
    ctx.config.Finish();
    const sensing::RobotConfig robot = sensing::LoadRobotConfigFile(ctx.system.robot_file);
    if (robot.sonar_ring.count != kRingSize) {
      throw InputError(ctx.system.robot_file, 0, "robot.sonar_ring.count",
                       fmt::format("the sonar stream carries {} sensors", kRingSize));
    }
    auto sonar = std::make_unique<SonarComponent>(
        cc, GateConfigFor(robot), Publish<msgs::SonarScanPubSubType>("robot/sonar"));
    Feed<msgs::SonarEchoPubSubType>("device/sonar/echo",
                                    [c = sonar.get()](const message::SonarEcho& e) { c->OnEcho(e); });
    return sonar;
  }
};

}  // namespace

std::unique_ptr<runtime::ProcessNode> MakeSonarNode() { return std::make_unique<SonarNode>(); }

}  // namespace stickrep::sonar
