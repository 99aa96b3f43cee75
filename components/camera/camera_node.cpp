#include "camera/camera_node.h"

#include <fmt/format.h>

#include "camera/frame_check.h"
#include "runtime/endpoint.h"
#include "sensing/robot_config.h"
#include "sensorsPubSubTypes.h"

namespace stickrep::camera {

namespace {

class CameraNode : public runtime::ProcessNode {
 public:
  void Configure(runtime::NodeContext& ctx) override {
    ctx_ = &ctx;
    const std::string device = ctx.config.Get<std::string>("device");
    if (device == "v4l2") {
      ctx.config.Fail("device", "the V4L2 camera driver is not built yet; use 'virtual'");
    } else if (device != "virtual") {
      ctx.config.Fail("device", "'" + device + "' is not one of: virtual, v4l2");
    }
    ctx.config.Finish();
    const sensing::RobotConfig robot = sensing::LoadRobotConfigFile(ctx.system.robot_file);
    width_px_ = static_cast<uint32_t>(robot.camera.image_width_px);
    height_px_ = static_cast<uint32_t>(robot.camera.image_height_px);
    writer_ = std::make_unique<runtime::Writer<msgs::ImagePubSubType>>(ctx.participant,
                                                                      "robot/camera/image");
    frames_ = std::make_unique<runtime::Reader<msgs::ImagePubSubType>>(
        ctx.participant, ctx.executor, "device/camera/frame",
        [this](const msgs::Image& m) { OnFrame(m); });
  }

  std::string Summary() const override {
    return fmt::format("{} frames of {} x {} px passed on", passed_, width_px_, height_px_);
  }

 private:
  void OnFrame(const msgs::Image& frame) {
    ctx_->counters.CountIn();
    const auto problem = CheckFrame(
        FrameShape{frame.width_px(), frame.height_px(), frame.step_bytes(), frame.encoding(),
                   frame.data().size()},
        width_px_, height_px_);
    if (problem) {
      ctx_->counters.Drop("device/camera/frame", *problem);
      return;
    }
    if (frame.header().stamp_ns() < last_stamp_ns_) {
      ctx_->counters.Drop("device/camera/frame", "time went backwards");
      return;
    }
    last_stamp_ns_ = frame.header().stamp_ns();
    msgs::Image out = frame;
    if (writer_->Publish(out, frame.header().stamp_ns())) {
      ctx_->counters.CountOut();
      passed_++;
    }
  }

  runtime::NodeContext* ctx_ = nullptr;
  uint32_t width_px_ = 0, height_px_ = 0;
  int64_t last_stamp_ns_ = 0;
  uint64_t passed_ = 0;
  std::unique_ptr<runtime::Writer<msgs::ImagePubSubType>> writer_;
  std::unique_ptr<runtime::Reader<msgs::ImagePubSubType>> frames_;
};

}  // namespace

std::unique_ptr<runtime::ProcessNode> MakeCameraNode() { return std::make_unique<CameraNode>(); }

}  // namespace stickrep::camera
