#include "sonar/sonar_gate.h"

#include <cmath>

#include "common/units.h"

namespace stickrep::sonar {

SonarGateConfig GateConfigFor(const sensing::RobotConfig& robot) {
  SonarGateConfig gate;
  gate.min_range_in = robot.sonar_ring.min_range_in;
  gate.max_range_in = robot.sonar_ring.max_range_in;
  gate.spacing_deg = robot.sonar_ring.spacing_deg;
  gate.head_radius_in = robot.sonar_ring.head_radius_in;
  gate.footprint_deg = robot.sonar_ring.footprint_deg;
  return gate;
}

namespace {

bool InRange(double r, const SonarGateConfig& c) {
  return r >= c.min_range_in && r <= c.max_range_in;
}

}  // namespace

GatedScan GateScan(const std::array<float, kRingSize>& raw_in, const SonarGateConfig& config) {
  GatedScan out;
  for (int k = 0; k < kRingSize; ++k) {
    const float r = raw_in[k];
    out.range_in[k] = r;
    if (!std::isfinite(r) || r < 0.0f) {
      out.state[k] = ReadingState::kMalformed;
      out.range_in[k] = 0.0f;
    } else if (r == 0.0f) {
      out.state[k] = ReadingState::kNoEcho;
    } else if (!InRange(r, config)) {
      out.state[k] = ReadingState::kOutOfRange;
    } else {
      out.state[k] = ReadingState::kValid;
    }
  }
  // Footprint: estimate the surface normal from the neighbours' echo points.
  const double step = DegToRad(config.spacing_deg);
  const double footprint = DegToRad(config.footprint_deg);
  std::array<ReadingState, kRingSize> gated = out.state;
  for (int k = 0; k < kRingSize; ++k) {
    if (out.state[k] != ReadingState::kValid) continue;
    const int a = (k + kRingSize - 1) % kRingSize;
    const int b = (k + 1) % kRingSize;
    if (out.state[a] != ReadingState::kValid || out.state[b] != ReadingState::kValid) continue;
    // Echo points in the head frame, sensor k along +x.
    const double ra = config.head_radius_in + out.range_in[a];
    const double rb = config.head_radius_in + out.range_in[b];
    const double ax = ra * std::cos(-step), ay = ra * std::sin(-step);
    const double bx = rb * std::cos(step), by = rb * std::sin(step);
    // The surface direction is a->b; its normal's angle to +x is the incidence.
    const double dx = bx - ax, dy = by - ay;
    const double incidence = std::abs(std::atan2(-dx, dy));  // angle of (dy, -dx) to +x
    const double phi = std::min(incidence, kPi - incidence);
    if (phi > footprint) gated[k] = ReadingState::kOutsideFootprint;
  }
  out.state = gated;
  for (int k = 0; k < kRingSize; ++k) out.valid_count += out.state[k] == ReadingState::kValid;
  return out;
}

}  // namespace stickrep::sonar
