#include "camera/camera_component.h"

#include <fmt/format.h>

#include "camera/frame_check.h"

namespace stickrep::camera {

void CameraComponent::OnFrame(const message::Image& frame) {
  const auto problem =
      CheckFrame(FrameShape{frame.width_px, frame.height_px, frame.step_bytes, frame.encoding,
                            frame.data.size()},
                 width_px_, height_px_);
  if (problem) {
    ctx_.counters.Drop("device/camera/frame", *problem);
    return;
  }
  if (frame.header.stamp_ns < last_stamp_ns_) {
    ctx_.counters.Drop("device/camera/frame", "time went backwards");
    return;
  }
  last_stamp_ns_ = frame.header.stamp_ns;
  if (images_.Publish(frame)) passed_++;
}

std::string CameraComponent::Summary() const {
  return fmt::format("{} frames of {} x {} px passed on", passed_, width_px_, height_px_);
}

}  // namespace stickrep::camera
