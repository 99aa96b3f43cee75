#include "camera/camera_node.h"

#include "camera/camera_component.h"
#include "runtime/component_node.h"
#include "sensing/robot_config.h"
#include "sensorsPubSubTypes.h"

namespace stickrep::camera {

namespace {

class CameraNode : public runtime::ComponentNode {
  std::unique_ptr<component::Component> Build(runtime::NodeContext& ctx,
                                              component::Context& cc) override {
    const std::string device = ctx.config.Get<std::string>("device");
    if (device == "v4l2") {
      ctx.config.Fail("device", "the V4L2 camera driver is not built yet; use 'virtual'");
    } else if (device != "virtual") {
      ctx.config.Fail("device", "'" + device + "' is not one of: virtual, v4l2");
    }
    ctx.config.Finish();
    const sensing::RobotConfig robot = sensing::LoadRobotConfigFile(ctx.system.robot_file);
    auto camera = std::make_unique<CameraComponent>(
        cc, static_cast<uint32_t>(robot.camera.image_width_px),
        static_cast<uint32_t>(robot.camera.image_height_px),
        Publish<msgs::ImagePubSubType>("robot/camera/image"));
    Feed<msgs::ImagePubSubType>("device/camera/frame",
                                [c = camera.get()](const message::Image& f) { c->OnFrame(f); });
    return camera;
  }
};

}  // namespace

std::unique_ptr<runtime::ProcessNode> MakeCameraNode() { return std::make_unique<CameraNode>(); }

}  // namespace stickrep::camera
