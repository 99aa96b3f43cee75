#include "sensing/sonar_model.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "common/units.h"

namespace stickrep::sensing {
namespace {

using ::testing::DoubleNear;

SonarRingModel Ring(double cone_deg = 23.6) {
  SonarRingModel r;
  r.spacing_rad = DegToRad(15.0);
  r.half_cone_rad = DegToRad(cone_deg) / 2.0;
  r.footprint_rad = DegToRad(15.0);
  return r;
}

TEST(SonarRingTest, BearingsStepFifteenDegreesFromTheCoaxialSensor) {
  SonarRingModel r = Ring();
  r.coaxial_sensor = 2;
  EXPECT_THAT(r.BearingOf(2), DoubleNear(0.0, 1e-12));
  EXPECT_THAT(r.BearingOf(4), DoubleNear(DegToRad(30.0), 1e-12));
  EXPECT_THAT(r.BearingOf(0), DoubleNear(DegToRad(-30.0), 1e-12));
  EXPECT_THAT(r.BearingOf(14), DoubleNear(kPi, 1e-12));
}

TEST(ReturnedRangeTest, InsideTheConeReturnsThePerpendicularFromTheSensor) {
  // Case 1: 72 in wall, sensor 10° off the normal, head radius 7.5 in.
  const auto d = ReturnedRange(Ring(), 72.0, DegToRad(10.0));
  ASSERT_TRUE(d.ok());
  EXPECT_THAT(*d, DoubleNear(72.0 - 7.5 * std::cos(DegToRad(10.0)), 1e-12));
}

TEST(ReturnedRangeTest, OutsideTheConeReturnsAlongTheNearestConeLimit) {
  // Case 2: sensor 30° off the normal; the cone limit is 30 - 11.8 = 18.2° off.
  const auto d = ReturnedRange(Ring(), 72.0, DegToRad(30.0));
  ASSERT_TRUE(d.ok());
  EXPECT_THAT(*d,
              DoubleNear((72.0 - 7.5 * std::cos(DegToRad(30.0))) / std::cos(DegToRad(18.2)), 1e-9));
}

TEST(ReturnedRangeTest, ACameraLookingAwayGetsNoEcho) {
  EXPECT_FALSE(ReturnedRange(Ring(), 72.0, DegToRad(120.0)).ok());
}

TEST(RangeAlongRayTest, InvertsTheForwardModel) {
  for (double inc : {0.0, 10.0, 25.0, 40.0, 60.0}) {
    const double d = *ReturnedRange(Ring(), 80.0, DegToRad(inc));
    const auto along = RangeAlongRay(Ring(), d, DegToRad(inc), DegToRad(inc - 2.1));
    ASSERT_TRUE(along.ok());
    EXPECT_THAT(*along, DoubleNear(80.0 / std::cos(DegToRad(inc - 2.1)), 1e-9)) << inc;
  }
}

// The printed formulas of §5.4.1 use a 24° cone (the 48°, 72° and 18° of the text).
class PrintedCasesTest : public ::testing::TestWithParam<double> {};

TEST_P(PrintedCasesTest, PrintedLeftFormulaMatchesTheGeometry) {
  const double delta = GetParam();
  const double fov = 55.817;
  const SonarRingModel ring = Ring(24.0);
  // The printed L is the sensor (90 - delta) - 30 = 60 - delta off the normal; its FOV
  // edge is 90 - delta - FOV/2 off it.
  const double sensor_inc = DegToRad(60.0 - delta);
  const double d_l = *ReturnedRange(ring, 72.0, sensor_inc);
  const PrintedCaseRanges p = PrintedExactRanges(d_l, 50.0, delta, fov, ring.head_radius_in);
  const double truth = 72.0 / std::cos(DegToRad(90.0 - delta - fov / 2.0));
  EXPECT_THAT(p.rl_in, DoubleNear(truth, 1e-9)) << "delta " << delta << " case " << p.case_number;
}

INSTANTIATE_TEST_SUITE_P(Cases1To3, PrintedCasesTest,
                         ::testing::Values(40.0, 47.0, 50.0, 60.0, 71.0, 75.0, 90.0));

TEST(PrintedCasesTest, PrintedCase2RightFormulaMatchesTheGeometry) {
  const double delta = 80.0, fov = 55.817;
  const SonarRingModel ring = Ring(24.0);
  const double d_r = *ReturnedRange(ring, 72.0, DegToRad(120.0 - delta));
  const PrintedCaseRanges p = PrintedExactRanges(50.0, d_r, delta, fov, ring.head_radius_in);
  EXPECT_EQ(p.case_number, 2);
  EXPECT_THAT(p.rr_in, DoubleNear(72.0 / std::cos(DegToRad(90.0 - delta + fov / 2.0)), 1e-9));
}

TEST(SurfaceErrorTest, TabulatedCellsAreReturnedExactly) {
  const auto c =
      SurfaceRangeError(Surface::kConcrete, DegToRad(15.0), UltrasoundExperiment::kTable42);
  ASSERT_TRUE(c.has_value());
  EXPECT_DOUBLE_EQ(c->mean_pct, 2.2);
  EXPECT_DOUBLE_EQ(c->sigma_pct, 0.03);
  const auto w = SurfaceRangeError(Surface::kWood, DegToRad(45.0), UltrasoundExperiment::kTable43);
  ASSERT_TRUE(w.has_value());
  EXPECT_DOUBLE_EQ(w->mean_pct, 22.0);
}

TEST(SurfaceErrorTest, InterpolatesBetweenTabulatedAngles) {
  const auto c =
      SurfaceRangeError(Surface::kConcrete, DegToRad(7.5), UltrasoundExperiment::kTable42);
  ASSERT_TRUE(c.has_value());
  EXPECT_THAT(c->mean_pct, DoubleNear((0.71 + 2.2) / 2.0, 1e-12));
}

TEST(SurfaceErrorTest, WorseOfBothPicksTheLargerMean) {
  const auto c =
      SurfaceRangeError(Surface::kWood, DegToRad(30.0), UltrasoundExperiment::kWorseOfBoth);
  ASSERT_TRUE(c.has_value());
  EXPECT_DOUBLE_EQ(c->mean_pct, 16.0);
}

TEST(SurfaceErrorTest, BeyondFortyFiveDegreesAndClothAtFortyFiveAreGross) {
  EXPECT_FALSE(
      SurfaceRangeError(Surface::kConcrete, DegToRad(50.0), UltrasoundExperiment::kTable42));
  EXPECT_FALSE(SurfaceRangeError(Surface::kCloth, DegToRad(45.0), UltrasoundExperiment::kTable42));
}

TEST(SurfaceErrorTest, AccurateFootprintIsFifteenDegreesForHardSurfacesOnly) {
  EXPECT_TRUE(InAccurateFootprint(Ring(), Surface::kConcrete, DegToRad(15.0)));
  EXPECT_FALSE(InAccurateFootprint(Ring(), Surface::kWood, DegToRad(16.0)));
  EXPECT_TRUE(InAccurateFootprint(Ring(), Surface::kCloth, 0.0));
  EXPECT_FALSE(InAccurateFootprint(Ring(), Surface::kCloth, DegToRad(10.0)));
}

}  // namespace
}  // namespace stickrep::sensing
