#pragma once

#include "component/component.h"
#include "messages/messages.h"

namespace stickrep::camera {

// The camera process's logic: frames from the device are checked against the robot's
// camera (size, encoding, buffer) and passed on as robot/camera/image; bad or out-of-order
// frames are dropped and counted.
class CameraComponent : public component::Component {
 public:
  CameraComponent(component::Context& ctx, uint32_t width_px, uint32_t height_px,
                  component::Publisher<message::Image>& images)
      : ctx_(ctx), width_px_(width_px), height_px_(height_px), images_(images) {}

  void OnFrame(const message::Image& frame);
  std::string Summary() const override;

 private:
  component::Context& ctx_;
  uint32_t width_px_, height_px_;
  component::Publisher<message::Image>& images_;
  int64_t last_stamp_ns_ = 0;
  uint64_t passed_ = 0;
};

}  // namespace stickrep::camera
