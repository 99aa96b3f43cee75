#include "camera/frame_check.h"

#include <fmt/format.h>

namespace stickrep::camera {

std::optional<std::string> CheckFrame(const FrameShape& f, std::uint32_t expected_width_px,
                                      std::uint32_t expected_height_px) {
  if (f.width_px == 0 || f.height_px == 0) {
    return fmt::format("empty frame ({} x {} px)", f.width_px, f.height_px);
  }
  if (f.encoding != "mono8") return fmt::format("unknown encoding '{}'", f.encoding);
  if (f.step_bytes < f.width_px) {
    return fmt::format("row step {} bytes is shorter than a {} px row", f.step_bytes, f.width_px);
  }
  const std::size_t expected = static_cast<std::size_t>(f.height_px) * f.step_bytes;
  if (f.data_bytes != expected) {
    return fmt::format("data is {} bytes, {} rows x {} bytes need {}", f.data_bytes, f.height_px,
                       f.step_bytes, expected);
  }
  if ((expected_width_px != 0 && f.width_px != expected_width_px) ||
      (expected_height_px != 0 && f.height_px != expected_height_px)) {
    return fmt::format("frame is {} x {} px, the camera is {} x {} px", f.width_px, f.height_px,
                       expected_width_px, expected_height_px);
  }
  return std::nullopt;
}

}  // namespace stickrep::camera
