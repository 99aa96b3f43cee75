#pragma once

#include <array>
#include <cstdint>

#include "sensing/robot_config.h"

namespace stickrep::sonar {

inline constexpr int kRingSize = 24;

// Why a reading is or is not passed on as valid (mirrors msgs::SonarReadingState).
enum class ReadingState : std::uint8_t {
  kValid,
  kNoEcho,
  kOutOfRange,
  kOutsideFootprint,
  kMalformed
};

// The ring's readings after gating.
struct GatedScan {
  std::array<float, kRingSize> range_in{};
  std::array<ReadingState, kRingSize> state{};
  int valid_count = 0;
};

// What the gate needs to know of the ring (from configs/robot.yaml).
struct SonarGateConfig {
  double min_range_in = 12.0;     // 1 ft (§4.3)
  double max_range_in = 420.0;    // 35 ft (§4.3)
  double spacing_deg = 15.0;      // angle between adjacent transducers
  double head_radius_in = 7.5;    // transducer faces sit on this radius
  double footprint_deg = 15.0;    // accurate ranging for incidence phi <= 15 deg (§4.3)
};

// The gate for the ring of a robot description (configs/robot.yaml).
SonarGateConfig GateConfigFor(const sensing::RobotConfig& robot);

// Gates one raw ring scan: malformed values (NaN, infinite, negative), no echo (0), ranges
// outside the 1-35 ft measuring range, and readings whose incidence on the surface is
// outside the accurate footprint. The incidence of sensor k is estimated from the surface
// line through the echo points of its two neighbours (§4.3: on concrete and wood the error
// stays small only for phi <= 15 deg); with a neighbour missing it cannot be judged and the
// reading is kept.
GatedScan GateScan(const std::array<float, kRingSize>& raw_in, const SonarGateConfig& config);

}  // namespace stickrep::sonar
