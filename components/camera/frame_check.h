#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace stickrep::camera {

// The shape a frame claims to have.
struct FrameShape {
  std::uint32_t width_px = 0;
  std::uint32_t height_px = 0;
  std::uint32_t step_bytes = 0;
  std::string encoding;
  std::size_t data_bytes = 0;
};

// Why a frame cannot be used, or nothing if it can: zero size, an encoding other than
// mono8, a row step shorter than a row, data whose length does not match height x step,
// or a size other than the configured camera's (expected_* of 0 skip that check).
std::optional<std::string> CheckFrame(const FrameShape& frame, std::uint32_t expected_width_px,
                                      std::uint32_t expected_height_px);

}  // namespace stickrep::camera
