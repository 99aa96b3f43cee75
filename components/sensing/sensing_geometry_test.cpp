#include "sensing/sensing_geometry.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace stickrep::sensing {
namespace {

using ::testing::DoubleNear;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

CameraModel Cam() { return CameraModel{}; }

TEST(CameraModelTest, ImageEdgeColumnsSitAtHalfTheFieldOfView) {
  const CameraModel cam = Cam();
  EXPECT_THAT(cam.AngleOfColumn(0.0), DoubleNear(-cam.fov_rad / 2.0, 1e-4));
  EXPECT_THAT(cam.AngleOfColumn(512.0), DoubleNear(cam.fov_rad / 2.0, 1e-4));
  EXPECT_THAT(cam.ColumnOfAngle(cam.AngleOfColumn(100.25)), DoubleNear(100.25, 1e-9));
}

TEST(TwoSideGeometryTest, FullFieldOfViewIsTheLawOfCosinesBase) {
  // Jambs at the image edges: the width is W_L, the visible wall, 2 * 72 * tan(27.9085°).
  const auto w = TwoSideWidth(Cam(), 72.0 / std::cos(Cam().fov_rad / 2),
                              72.0 / std::cos(Cam().fov_rad / 2), {0.0, 512.0});
  ASSERT_TRUE(w.ok()) << w.message();
  EXPECT_THAT(*w, DoubleNear(2.0 * 72.0 * std::tan(Cam().fov_rad / 2.0), 0.01));
}

TEST(TwoSideGeometryTest, ThirtySixInchDoorSquareOnAtSixFeetMeasuresThirtySix) {
  const auto t = MakeScene(Cam(), {72.0, kPi / 2, 36.0, 0.0});
  ASSERT_TRUE(t.ok());
  // Hand check of the footprints: atan(18/72) = 14.036°, column 256 -/+ tan(14.036°)/k.
  EXPECT_THAT(t->footprints.lj_px, DoubleNear(256.0 - 0.25 / (0.012414 / 6.0), 1e-6));
  const auto w = TwoSideWidth(Cam(), t->rl_in, t->rr_in, t->footprints);
  ASSERT_TRUE(w.ok());
  EXPECT_THAT(*w, DoubleNear(36.0, 1e-9));
}

TEST(TwoSideGeometryTest, RecoversTheWidthAtObliqueStaresOnBothSides) {
  for (double stare_deg : {50.0, 70.0, 110.0, 130.0}) {
    const auto t = MakeScene(Cam(), {72.0, DegToRad(stare_deg), 36.0, 0.0});
    ASSERT_TRUE(t.ok()) << stare_deg;
    const auto w = TwoSideWidth(Cam(), t->rl_in, t->rr_in, t->footprints);
    ASSERT_TRUE(w.ok()) << stare_deg;
    EXPECT_THAT(*w, DoubleNear(36.0, 1e-9)) << "stare " << stare_deg;
  }
}

TEST(ShortSideGeometryTest, FieldOfViewEdgesVariantIsExact) {
  const auto t = MakeScene(Cam(), {72.0, DegToRad(70.0), 36.0, 0.0});
  ASSERT_TRUE(t.ok());
  const auto w =
      ShortSideWidth(Cam(), 72.0, t->theta_rad, t->footprints, ShortSideEdges::kFieldOfViewEdges);
  ASSERT_TRUE(w.ok());
  EXPECT_THAT(*w, DoubleNear(36.0, 1e-9));
}

TEST(ShortSideGeometryTest, PrintedFormulaOverestimatesSquareOnByTheRayApproximation) {
  // RL = sdis / sin(pi/3) = 83.14 in along the 30° ray, used as the 27.9° edge: the width
  // grows by L/RL = cos(27.9085°)/cos(30°) = 1.0204 (Table 5.2, L -> RL 2.0 %).
  const auto t = MakeScene(Cam(), {72.0, kPi / 2, 36.0, 0.0});
  ASSERT_TRUE(t.ok());
  const auto w = ShortSideWidth(Cam(), 72.0, 0.0, t->footprints);
  ASSERT_TRUE(w.ok());
  EXPECT_THAT(*w, DoubleNear(36.0 * std::cos(Cam().fov_rad / 2) / std::cos(kPi / 6), 1e-9));
}

TEST(ShortSideGeometryTest, SidesFollowTheSinesOfSection53) {
  double rl = 0, rr = 0;
  ShortSideSidesT(Cam(), 60.0, DegToRad(10.0), ShortSideEdges::kPaperSensorRays, &rl, &rr);
  EXPECT_THAT(rl, DoubleNear(60.0 / std::sin(DegToRad(70.0)), 1e-12));
  EXPECT_THAT(rr, DoubleNear(60.0 / std::sin(DegToRad(50.0)), 1e-12));
}

TEST(SensingGeometryErrorsTest, RejectsNaNNegativeAndZeroRanges) {
  const Footprints fp{200, 300};
  EXPECT_EQ(TwoSideWidth(Cam(), kNaN, 80, fp).error(), SensingError::kBadSonarRange);
  EXPECT_EQ(TwoSideWidth(Cam(), 80, -1, fp).error(), SensingError::kBadSonarRange);
  EXPECT_EQ(ShortSideWidth(Cam(), 0.0, 0.0, fp).error(), SensingError::kBadSonarRange);
}

TEST(SensingGeometryErrorsTest, RejectsFootprintsOutsideTheImageOrOutOfOrder) {
  EXPECT_EQ(TwoSideWidth(Cam(), 80, 80, {-1, 300}).error(), SensingError::kBadFootprint);
  EXPECT_EQ(TwoSideWidth(Cam(), 80, 80, {200, 513}).error(), SensingError::kBadFootprint);
  EXPECT_EQ(TwoSideWidth(Cam(), 80, 80, {300, 300}).error(), SensingError::kBadFootprint);
  EXPECT_EQ(TwoSideWidth(Cam(), 80, 80, {310, 300}).error(), SensingError::kBadFootprint);
  EXPECT_EQ(TwoSideWidth(Cam(), 80, 80, {kNaN, 300}).error(), SensingError::kBadFootprint);
}

TEST(SensingGeometryErrorsTest, RejectsStaresOutsideTheShortSideInterval) {
  const Footprints fp{200, 300};
  EXPECT_EQ(ShortSideWidth(Cam(), 72, kPi / 3, fp).error(), SensingError::kStareOutOfRange);
  EXPECT_EQ(ShortSideWidth(Cam(), 72, -kPi / 3, fp).error(), SensingError::kStareOutOfRange);
  EXPECT_EQ(ShortSideWidth(Cam(), 72, kNaN, fp).error(), SensingError::kStareOutOfRange);
  EXPECT_TRUE(ShortSideWidth(Cam(), 72, kPi / 3 - 0.2, fp).ok());
}

TEST(SensingGeometryErrorsTest, ErrorMessagesNameTheValue) {
  const auto w = ShortSideWidth(Cam(), 72, DegToRad(75.0), {200, 300});
  EXPECT_THAT(w.message(), ::testing::HasSubstr("75"));
}

TEST(MakeSceneTest, RejectsADoorOutsideTheFieldOfView) {
  EXPECT_EQ(MakeScene(Cam(), {72.0, kPi / 2, 36.0, 40.0}).error(), SensingError::kBadFootprint);
}

}  // namespace
}  // namespace stickrep::sensing
