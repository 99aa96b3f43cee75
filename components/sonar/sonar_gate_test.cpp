#include "sonar/sonar_gate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/units.h"

namespace stickrep::sonar {
namespace {

// Ranges a ring at the origin reads from an infinite wall at perpendicular distance d
// (from the head centre), sensor 0 facing the wall square on; sensors that face away or
// beyond 60 deg read no echo.
std::array<float, kRingSize> WallScan(double d_in, const SonarGateConfig& c) {
  std::array<float, kRingSize> raw{};
  for (int k = 0; k < kRingSize; ++k) {
    const double bearing = DegToRad(c.spacing_deg) * (k <= 12 ? k : k - kRingSize);
    if (std::abs(bearing) > DegToRad(60.0)) continue;
    raw[k] = static_cast<float>(d_in / std::cos(bearing) - c.head_radius_in);
  }
  return raw;
}

TEST(SonarGateTest, SquareOnWallReadingIsValidAndObliqueOnesAreOutsideTheFootprint) {
  const SonarGateConfig c;
  const GatedScan g = GateScan(WallScan(72.0, c), c);
  EXPECT_EQ(g.state[0], ReadingState::kValid);
  EXPECT_EQ(g.state[3], ReadingState::kOutsideFootprint);   // 45 deg incidence
  EXPECT_EQ(g.state[21], ReadingState::kOutsideFootprint);  // -45 deg
  EXPECT_EQ(g.state[2], ReadingState::kOutsideFootprint);   // 30 deg
  EXPECT_EQ(g.state[12], ReadingState::kNoEcho);
}

TEST(SonarGateTest, MalformedValuesAreFlaggedAndZeroed) {
  const SonarGateConfig c;
  std::array<float, kRingSize> raw{};
  raw[1] = std::numeric_limits<float>::quiet_NaN();
  raw[2] = -5.0f;
  raw[3] = std::numeric_limits<float>::infinity();
  const GatedScan g = GateScan(raw, c);
  for (int k : {1, 2, 3}) {
    EXPECT_EQ(g.state[k], ReadingState::kMalformed) << k;
    EXPECT_EQ(g.range_in[k], 0.0f) << k;
  }
}

TEST(SonarGateTest, RangesOutsideOneToThirtyFiveFeetAreOutOfRange) {
  const SonarGateConfig c;
  std::array<float, kRingSize> raw{};
  raw[0] = 6.0f;
  raw[6] = 500.0f;
  const GatedScan g = GateScan(raw, c);
  EXPECT_EQ(g.state[0], ReadingState::kOutOfRange);
  EXPECT_EQ(g.state[6], ReadingState::kOutOfRange);
}

TEST(SonarGateTest, ReadingWithoutBothNeighboursIsKept) {
  const SonarGateConfig c;
  std::array<float, kRingSize> raw{};
  raw[8] = 100.0f;
  const GatedScan g = GateScan(raw, c);
  EXPECT_EQ(g.state[8], ReadingState::kValid);
  EXPECT_EQ(g.valid_count, 1);
}

}  // namespace
}  // namespace stickrep::sonar
