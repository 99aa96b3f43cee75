#include "world/camera_renderer.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "common/units.h"

namespace stickrep::world {
namespace {

using ::testing::DoubleNear;
using ::testing::SizeIs;

constexpr double kDoorStartIn = 120.0;
constexpr double kDoorWidthIn = 36.0;
constexpr double kHallwayWidthIn = 240.0;  // wide enough to stand 12 ft from the wall

Scene DoorScene() {
  HallwayOptions options;
  options.width_in = kHallwayWidthIn;
  return Scene(MakeStraightHallway({HallwayFeature::Wall(kDoorStartIn),
                                    HallwayFeature::Door(kDoorWidthIn), HallwayFeature::Wall(120)},
                                   options));
}

// Robot heading +x with the camera looking at the feature wall (+y) from `range_in`,
// centred on the door.
Pose2d FacingDoor(double range_in, double along_in = 0.0) {
  return {kDoorStartIn + kDoorWidthIn / 2.0 + along_in, kHallwayWidthIn / 2.0 - range_in, 0.0};
}

CameraModel IdealCamera() {
  CameraModel camera;
  camera.k1 = 0.0;
  camera.roll_deg = 0.0;
  return camera;
}

Illumination NoNoise() {
  Illumination light;
  light.noise_stddev = 0.0;
  return light;
}

// Sub-pixel column where row `v` crosses the mean of the levels at columns lo and hi,
// between them (linear interpolation between pixel centres).
double EdgeColumn(const cv::Mat& image, int v, int lo, int hi) {
  const double a = image.at<std::uint8_t>(v, lo);
  const double b = image.at<std::uint8_t>(v, hi);
  const double mid = (a + b) / 2.0;
  for (int u = lo; u < hi; ++u) {
    const double p = image.at<std::uint8_t>(v, u);
    const double q = image.at<std::uint8_t>(v, u + 1);
    if ((p - mid) * (q - mid) <= 0.0 && p != q) return u + (mid - p) / (q - p);
  }
  return -1.0;
}

TEST(CameraModelTest, FocalLengthPutsTheImageEdgeAtHalfTheFieldOfView) {
  const CameraModel camera;
  EXPECT_THAT(camera.focal_px(), DoubleNear(256.0 / std::tan(DegToRad(55.817 / 2.0)), 1e-9));
  EXPECT_THAT(camera.focal_px(), DoubleNear(483.3, 0.1));
}

TEST(CameraRendererTest, FrameIsMono8OfTheConfiguredSize) {
  const CameraRenderer renderer{CameraModel{}};
  std::mt19937_64 rng(3);
  const RenderedFrame frame = renderer.Render(DoorScene(), FacingDoor(72.0), {}, rng);
  EXPECT_EQ(frame.image.type(), CV_8UC1);
  EXPECT_EQ(frame.image.cols, 512);
  EXPECT_EQ(frame.image.rows, 480);
}

TEST(CameraRendererTest, JambTruthMatchesThePinholeProjection) {
  const CameraRenderer renderer(IdealCamera());
  const FrameTruth truth = renderer.Truth(DoorScene(), FacingDoor(72.0));
  ASSERT_THAT(truth.doors, SizeIs(1));
  const double f = IdealCamera().focal_px();
  const double depth = 72.0 - 0.1;  // the jamb edge is on the casing face, 0.1 in proud
  EXPECT_THAT(truth.doors[0].left_column_px, DoubleNear(255.5 - f * 18.0 / depth, 1e-9));
  EXPECT_THAT(truth.doors[0].right_column_px, DoubleNear(255.5 + f * 18.0 / depth, 1e-9));
  EXPECT_TRUE(truth.doors[0].both_jambs_visible);
  EXPECT_EQ(truth.doors[0].class_in, 36);
}

TEST(CameraRendererTest, RenderedJambEdgeLiesWithinHalfAPixelOfItsProjection) {
  const CameraRenderer renderer(IdealCamera());
  std::mt19937_64 rng(3);
  // Off-centre by 7.3 in so the edges fall between pixel centres.
  const RenderedFrame frame = renderer.Render(DoorScene(), FacingDoor(72.0, 7.3), NoNoise(), rng);
  ASSERT_THAT(frame.truth.doors, SizeIs(1));
  const int row = 240;
  for (const JambTruth& jamb : frame.truth.jambs) {
    // The inner edge: frame casing on one side, the leaf on the other, 3 in = 20 px apart
    // from the outer edge; look in a +-6 px window.
    const int c = static_cast<int>(std::lround(jamb.column_px));
    const double edge = EdgeColumn(frame.image, row, c - 6, c + 6);
    EXPECT_THAT(edge, DoubleNear(jamb.column_px, 0.5)) << "jamb of door " << jamb.door_index;
  }
}

TEST(CameraRendererTest, AxisRangeIsTheDistanceToTheWallAlongTheOpticalAxis) {
  const CameraRenderer renderer{CameraModel{}};
  const FrameTruth truth = renderer.Truth(DoorScene(), FacingDoor(100.0, 80.0));
  EXPECT_THAT(truth.axis_range_in, DoubleNear(100.0, 1e-9));
  EXPECT_THAT(truth.X_WC.theta_rad, DoubleNear(kPi / 2.0, 1e-12));
}

TEST(CameraRendererTest, DoorOutsideTheFieldOfViewHasNoTruth) {
  const CameraRenderer renderer{CameraModel{}};
  const FrameTruth truth = renderer.Truth(DoorScene(), FacingDoor(72.0, -100.0));
  EXPECT_THAT(truth.doors, SizeIs(0));
  EXPECT_THAT(truth.jambs, SizeIs(0));
}

TEST(CameraRendererTest, SameSeedGivesTheSameFrameAndAnotherSeedAnother) {
  const CameraRenderer renderer{CameraModel{}};
  const Scene scene = DoorScene();
  std::mt19937_64 a(11), b(11), c(12);
  const cv::Mat fa = renderer.Render(scene, FacingDoor(72.0), {}, a).image;
  const cv::Mat fb = renderer.Render(scene, FacingDoor(72.0), {}, b).image;
  const cv::Mat fc = renderer.Render(scene, FacingDoor(72.0), {}, c).image;
  EXPECT_EQ(cv::norm(fa, fb, cv::NORM_L1), 0.0);
  EXPECT_GT(cv::norm(fa, fc, cv::NORM_L1), 0.0);
}

TEST(CameraRendererTest, RollTiltsVerticalEdgesByTheRollAngle) {
  CameraModel camera = IdealCamera();
  camera.roll_deg = 10.0;
  const CameraRenderer renderer(camera);
  std::mt19937_64 rng(3);
  const RenderedFrame frame = renderer.Render(DoorScene(), FacingDoor(72.0, 5.0), NoNoise(), rng);
  ASSERT_THAT(frame.truth.jambs, SizeIs(2));
  const JambTruth& jamb = frame.truth.jambs[0];
  const int c = static_cast<int>(std::lround(jamb.column_px));
  // 60 rows above the centre the edge has moved tan(10°) * 60 = 10.6 px to the left.
  const double upper = EdgeColumn(frame.image, 240 - 60, c - 22, c - 2);
  const double centre = EdgeColumn(frame.image, 240, c - 6, c + 6);
  EXPECT_THAT(centre, DoubleNear(jamb.column_px, 0.6));
  EXPECT_THAT(centre - upper, DoubleNear(std::tan(DegToRad(10.0)) * 60.0, 1.0));
}

TEST(CameraRendererTest, PincushionPushesOffCentrePointsOutward) {
  CameraModel camera = IdealCamera();
  const CameraRenderer ideal(camera);
  camera.k1 = 0.1;
  const CameraRenderer pincushion(camera);
  const Pose2d X_WC = ideal.CameraPose(FacingDoor(72.0));
  const Eigen::Vector3d corner{kDoorStartIn, kHallwayWidthIn / 2.0, 75.0};
  const auto p_ideal = ideal.Project(X_WC, corner);
  const auto p_pin = pincushion.Project(X_WC, corner);
  ASSERT_TRUE(p_ideal && p_pin);
  EXPECT_LT(p_pin->x(), p_ideal->x());  // left of centre moves further left
  EXPECT_LT(p_pin->y(), p_ideal->y());  // above centre moves further up
}

TEST(CameraRendererTest, OpenDoorStillReportsBothJambs) {
  HallwayOptions options;
  options.width_in = kHallwayWidthIn;
  const Scene scene(MakeStraightHallway(
      {HallwayFeature::Wall(kDoorStartIn),
       HallwayFeature::Door(kDoorWidthIn, DoorState::kOpenInward, DegToRad(90.0)),
       HallwayFeature::Wall(120)},
      options));
  const CameraRenderer renderer{CameraModel{}};
  const FrameTruth truth = renderer.Truth(scene, FacingDoor(72.0));
  ASSERT_THAT(truth.doors, SizeIs(1));
  EXPECT_TRUE(truth.doors[0].both_jambs_visible);
  EXPECT_EQ(truth.doors[0].state, DoorState::kOpenInward);
}

}  // namespace
}  // namespace stickrep::world
