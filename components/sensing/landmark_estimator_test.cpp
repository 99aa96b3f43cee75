#include "sensing/landmark_estimator.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace stickrep::sensing {
namespace {

using ::testing::DoubleNear;
using ::testing::HasSubstr;

// A scan of a plane wall `distance_in` from the ring centre whose normal is `theta_rad` from
// the optical axis (theta > 0: axis rotated toward the image's right of the normal).
SonarScan WallScan(const LandmarkEstimator& est, double distance_in, double theta_rad) {
  SonarScan s;
  for (int k = 0; k < est.ring().count; ++k) {
    const auto d = ReturnedRange(est.ring(), distance_in, est.ring().BearingOf(k) + theta_rad);
    const bool ok = d.ok() && est.ring().InRange(*d);
    s.ranges_in.push_back(ok ? *d : 0.0);
    s.valid.push_back(ok);
  }
  return s;
}

JambCandidate Door(const LandmarkEstimator& est, double width_in, double stare_deg,
                   double confidence, double offset_in = 0.0) {
  const auto t = MakeScene(est.camera(), {72.0, DegToRad(stare_deg), width_in, offset_in});
  EXPECT_TRUE(t.ok()) << t.message();
  return {t->footprints, confidence};
}

class LandmarkEstimatorTest : public ::testing::Test {
 protected:
  RobotConfig robot_;
  LandmarkEstimator est_{robot_};
};

TEST_F(LandmarkEstimatorTest, ClosedThirtySixInchDoorSquareOnIsClassThirtySix) {
  const auto obs = est_.Estimate(WallScan(est_, 72.0, 0.0), {Door(est_, 36.0, 90.0, 1.0)});
  ASSERT_TRUE(obs.ok()) << obs.message();
  EXPECT_EQ(obs->door_class, DoorClass::k36);
  // The printed Short Side formula reads 2.0 % wide square-on (Table 5.2, L -> RL).
  EXPECT_THAT(obs->width_in, DoubleNear(36.0 * 1.0204, 0.01));
  EXPECT_THAT(obs->range_in, DoubleNear(72.0, 1e-9));
  EXPECT_THAT(obs->look_angle_rad, DoubleNear(kPi / 2.0, 1e-12));
  EXPECT_TRUE(obs->in_envelope);
  EXPECT_FALSE(obs->open_door);
}

TEST_F(LandmarkEstimatorTest, FieldOfViewEdgeVariantMeasuresTheDoorExactly) {
  LandmarkEstimatorConfig cfg;
  cfg.short_side_edges = ShortSideEdges::kFieldOfViewEdges;
  const LandmarkEstimator est(robot_, cfg);
  const auto obs = est.Estimate(WallScan(est, 72.0, 0.0), {Door(est, 36.0, 90.0, 1.0)});
  ASSERT_TRUE(obs.ok());
  EXPECT_THAT(obs->width_in, DoubleNear(36.0, 1e-9));
}

TEST_F(LandmarkEstimatorTest, TwoSideGeometryIsSelectable) {
  LandmarkEstimatorConfig cfg;
  cfg.geometry = Geometry::kTwoSide;
  const LandmarkEstimator est(robot_, cfg);
  const auto obs = est.Estimate(WallScan(est, 72.0, 0.0), {Door(est, 40.0, 90.0, 1.0)});
  ASSERT_TRUE(obs.ok()) << obs.message();
  // The 30° sensors return along their cone limit (Case 2): shorter than the FOV edges, so
  // the Two Side reads narrow square-on.
  EXPECT_LT(obs->width_in, 40.0);
  EXPECT_GT(obs->width_in, 35.0);
}

TEST_F(LandmarkEstimatorTest, CandidatesAreTriedInOrderOfConfidence) {
  const auto obs = est_.Estimate(WallScan(est_, 72.0, 0.0),
                                 {Door(est_, 36.0, 90.0, 0.4), Door(est_, 40.0, 90.0, 0.9)});
  ASSERT_TRUE(obs.ok());
  EXPECT_EQ(obs->candidate_index, 1);
  EXPECT_EQ(obs->door_class, DoorClass::k40);
}

TEST_F(LandmarkEstimatorTest, CandidateOutsideEveryClassFallsThroughToTheNext) {
  const auto obs = est_.Estimate(WallScan(est_, 72.0, 0.0),
                                 {Door(est_, 20.0, 90.0, 0.9), Door(est_, 30.0, 90.0, 0.5)});
  ASSERT_TRUE(obs.ok());
  EXPECT_EQ(obs->candidate_index, 1);
  EXPECT_EQ(obs->door_class, DoorClass::k30);
}

TEST_F(LandmarkEstimatorTest, AllCandidatesOutsideEveryClassAreRejected) {
  const auto obs = est_.Estimate(WallScan(est_, 72.0, 0.0),
                                 {Door(est_, 20.0, 90.0, 0.9), Door(est_, 48.0, 90.0, 0.5)});
  EXPECT_EQ(obs.error(), SensingError::kOutsideEveryClass);
  EXPECT_THAT(obs.message(), HasSubstr("widths"));
}

TEST_F(LandmarkEstimatorTest, CandidatesBelowTheConfidenceThresholdAreIgnored) {
  LandmarkEstimatorConfig cfg;
  cfg.min_confidence = 0.5;
  const LandmarkEstimator est(robot_, cfg);
  EXPECT_EQ(est.Estimate(WallScan(est, 72.0, 0.0), {Door(est, 36.0, 90.0, 0.3)}).error(),
            SensingError::kNoCandidate);
  EXPECT_EQ(est.Estimate(WallScan(est, 72.0, 0.0), {}).error(), SensingError::kNoCandidate);
}

TEST_F(LandmarkEstimatorTest, OpenDoorDepthIsInterpolatedFromTheFlanks) {
  SonarScan scan = WallScan(est_, 72.0, 0.0);
  scan.ranges_in[0] += 40.0;  // the coaxial sensor looks through the open door
  const auto obs = est_.Estimate(scan, {Door(est_, 36.0, 90.0, 1.0)});
  ASSERT_TRUE(obs.ok()) << obs.message();
  EXPECT_TRUE(obs->open_door);
  EXPECT_EQ(obs->door_class, DoorClass::k36);
  EXPECT_THAT(obs->range_in, DoubleNear(72.0, 0.05));
}

TEST_F(LandmarkEstimatorTest, ObliqueStareIsOutsideTheEnvelope) {
  // Wall normal 30° to the left of the axis: the sensor two spacings left is nearest.
  const auto obs =
      est_.Estimate(WallScan(est_, 72.0, DegToRad(-30.0)), {Door(est_, 36.0, 60.0, 1.0)});
  ASSERT_TRUE(obs.ok()) << obs.message();
  EXPECT_THAT(obs->theta_rad, DoubleNear(DegToRad(-30.0), 1e-12));
  EXPECT_FALSE(obs->in_envelope);
}

TEST_F(LandmarkEstimatorTest, LateralOffsetBeyondOneFootIsOutsideTheEnvelope) {
  const auto scan = WallScan(est_, 72.0, 0.0);
  EXPECT_TRUE(est_.Estimate(scan, {Door(est_, 36.0, 90.0, 1.0)}, 11.0)->in_envelope);
  EXPECT_FALSE(est_.Estimate(scan, {Door(est_, 36.0, 90.0, 1.0)}, 13.0)->in_envelope);
}

TEST_F(LandmarkEstimatorTest, ValidFlaggedBadRangesAreErrors) {
  for (double bad : {std::numeric_limits<double>::quiet_NaN(), -5.0, 5.0, 500.0}) {
    SonarScan scan = WallScan(est_, 72.0, 0.0);
    scan.ranges_in[3] = bad;
    const auto obs = est_.Estimate(scan, {Door(est_, 36.0, 90.0, 1.0)});
    EXPECT_EQ(obs.error(), SensingError::kBadSonarRange) << bad;
    EXPECT_THAT(obs.message(), HasSubstr("sensor 3"));
  }
}

TEST_F(LandmarkEstimatorTest, InvalidFlaggedReadingsAreIgnored) {
  SonarScan scan = WallScan(est_, 72.0, 0.0);
  scan.ranges_in[12] = std::numeric_limits<double>::quiet_NaN();
  scan.valid[12] = false;
  EXPECT_TRUE(est_.Estimate(scan, {Door(est_, 36.0, 90.0, 1.0)}).ok());
}

TEST_F(LandmarkEstimatorTest, WrongSensorCountIsAnError) {
  SonarScan scan = WallScan(est_, 72.0, 0.0);
  scan.ranges_in.pop_back();
  EXPECT_EQ(est_.Estimate(scan, {Door(est_, 36.0, 90.0, 1.0)}).error(),
            SensingError::kBadSonarRange);
}

TEST_F(LandmarkEstimatorTest, MalformedFootprintsAreErrors) {
  const auto scan = WallScan(est_, 72.0, 0.0);
  EXPECT_EQ(est_.Estimate(scan, {{{300.0, 200.0}, 1.0}}).error(), SensingError::kBadFootprint);
  EXPECT_EQ(est_.Estimate(scan, {{{-3.0, 200.0}, 1.0}}).error(), SensingError::kBadFootprint);
  EXPECT_EQ(est_.Estimate(scan, {{{100.0, 600.0}, 1.0}}).error(), SensingError::kBadFootprint);
  EXPECT_EQ(est_.Estimate(scan, {{{100.0, 200.0}, std::nan("")}}).error(),
            SensingError::kBadFootprint);
}

TEST_F(LandmarkEstimatorTest, NoValidSonarNearTheAxisIsAnError) {
  SonarScan scan = WallScan(est_, 72.0, 0.0);
  for (int k = 0; k < 24; ++k) scan.valid[k] = false;
  EXPECT_EQ(est_.Estimate(scan, {Door(est_, 36.0, 90.0, 1.0)}).error(),
            SensingError::kNoValidSonar);
}

}  // namespace
}  // namespace stickrep::sensing
