#pragma once

#include <cstdint>
#include <string>

#include "sensing/robot_config.h"

namespace stickrep::measure {

// Writes one PNG per clutter class of world::RealismOptions (and a clean and an all-on
// frame) to `dir`: a hallway with doors rendered with that feature alone, the landmark
// pipeline run on it, and its detections drawn (DrawDetections). Returns one report line
// per frame: what the pipeline sensed. Throws InputError when a file cannot be written.
std::string WriteSampleFrames(const std::string& dir, const sensing::RobotConfig& robot,
                              std::uint64_t seed);

}  // namespace stickrep::measure
