// The detector on frames drawn by the simulated world, against the renderer's ground truth.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "common/units.h"
#include "vision/ribbon_detector.h"
#include "world/camera_renderer.h"
#include "world/scene.h"
#include "world/world.h"

namespace stickrep::vision {
namespace {

using world::CameraModel;
using world::CameraRenderer;
using world::DoorState;
using world::HallwayFeature;
using world::HallwayOptions;
using world::Illumination;
using world::Pose2d;
using world::RenderedFrame;
using world::Scene;

constexpr double kDoorStartIn = 120.0;
constexpr double kHallwayWidthIn = 240.0;  // room to stand 12 ft from the wall
constexpr std::uint64_t kSeed = 1234;
// §4.1.1 quality asked of footprints here: within 2 px of the true jamb column.
constexpr double kJambTolerancePx = 2.0;
// Pairs considered: the classifier walks candidates in confidence order (§4.1.2), so a
// door must be among the first few to be classified.
constexpr int kTopPairs = 5;

Scene DoorScene(double width_in, DoorState state = DoorState::kClosed, double angle_deg = 0.0) {
  HallwayOptions options;
  options.width_in = kHallwayWidthIn;
  return Scene(world::MakeStraightHallway(
      {HallwayFeature::Wall(kDoorStartIn),
       HallwayFeature::Door(width_in, state, DegToRad(angle_deg)), HallwayFeature::Wall(240)},
      options));
}

// Robot heading +x with the camera looking at the feature wall from range_in; the optical
// axis meets the wall `along_in` inches past the door centre (the door then appears left of
// the image centre for positive along_in).
Pose2d Facing(double width_in, double range_in, double along_in = 0.0) {
  return {kDoorStartIn + width_in / 2.0 + along_in, kHallwayWidthIn / 2.0 - range_in, 0.0};
}

// Index (in confidence order) of the first pair whose jambs lie within tolerance of the
// truth, or -1.
int MatchingPair(const RibbonDetection& det, double left_px, double right_px) {
  for (size_t i = 0; i < det.pairs.size(); ++i) {
    if (std::abs(det.pairs[i].left_px - left_px) <= kJambTolerancePx &&
        std::abs(det.pairs[i].right_px - right_px) <= kJambTolerancePx) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

std::string Describe(const RibbonDetection& det) {
  std::string s = "threshold " + std::to_string(det.threshold) + "; footprints:";
  for (const Footprint& f : det.footprints) {
    s += " " + std::to_string(f.column_px) + "(w" + std::to_string(f.weight).substr(0, 4) + ",r" +
         std::to_string(f.rows_hit) + ")";
  }
  s += "; pairs:";
  for (size_t i = 0; i < det.pairs.size() && i < 8; ++i) {
    s += " [" + std::to_string(det.pairs[i].left_px) + "," + std::to_string(det.pairs[i].right_px) +
         " c" + std::to_string(det.pairs[i].confidence).substr(0, 5) + "]";
  }
  return s;
}

struct Outcome {
  RenderedFrame frame;
  DetectResult result;
};

Outcome RenderAndDetect(const Scene& scene, const Pose2d& X_WR, CameraModel camera = {},
                        Illumination light = {}, RibbonDetectorParams params = {}) {
  const CameraRenderer renderer(camera);
  std::mt19937_64 rng(kSeed);
  Outcome out{renderer.Render(scene, X_WR, light, rng), {}};
  out.result = RibbonDetector(params).Detect(out.frame.image, out.frame.truth.axis_range_in);
  return out;
}

void ExpectDoorFound(const Outcome& out, double width_in, double range_in) {
  ASSERT_TRUE(out.result.ok()) << out.result.message;
  ASSERT_EQ(out.frame.truth.doors.size(), 1u);
  const world::DoorTruth& door = out.frame.truth.doors[0];
  ASSERT_TRUE(door.both_jambs_visible);
  const RibbonDetection& det = out.result.detection;
  const int k = MatchingPair(det, door.left_column_px, door.right_column_px);
  ASSERT_GE(k, 0) << "truth " << door.left_column_px << ", " << door.right_column_px << "; "
                  << Describe(det);
  EXPECT_LT(k, kTopPairs) << Describe(det);
  // Kept in the XML report (--gtest_output=xml) for docs/vision.md.
  ::testing::Test::RecordProperty("pair_rank", k);
  ::testing::Test::RecordProperty("left_error_px",
                                  std::to_string(det.pairs[k].left_px - door.left_column_px));
  ::testing::Test::RecordProperty("right_error_px",
                                  std::to_string(det.pairs[k].right_px - door.right_column_px));
  // Width in pixels consistent with the truth and, roughly, with the pinhole f * W / R.
  // The width is the difference of two jambs, each within the tolerance.
  EXPECT_NEAR(det.pairs[k].width_px, door.right_column_px - door.left_column_px,
              2.0 * kJambTolerancePx);
  const double f = CameraModel{}.focal_px();
  EXPECT_NEAR(det.pairs[k].width_px / (f * width_in / range_in), 1.0, 0.05);
}

TEST(RibbonDetectorRenderedTest, FindsClosedDoorAtSixFeet) {
  const Outcome out = RenderAndDetect(DoorScene(36), Facing(36, 72.0, 4.3));
  ExpectDoorFound(out, 36, 72.0);
}

TEST(RibbonDetectorRenderedTest, FindsClosedDoorAtTwelveFeet) {
  const Outcome out = RenderAndDetect(DoorScene(36), Facing(36, 144.0, -20.0));
  ExpectDoorFound(out, 36, 144.0);
}

TEST(RibbonDetectorRenderedTest, FindsDoorWithTenDegreesOfRollAtTwelveFeet) {
  // §4.1.1: "misalignment angle as great as 10 degrees from vertical at a distance of 12 feet".
  CameraModel camera;
  camera.roll_deg = 10.0;
  const Outcome out = RenderAndDetect(DoorScene(36), Facing(36, 144.0, 10.0), camera);
  ExpectDoorFound(out, 36, 144.0);
}

TEST(RibbonDetectorRenderedTest, FindsDoorWithTenDegreesOfNegativeRollAtSixFeet) {
  CameraModel camera;
  camera.roll_deg = -10.0;
  const Outcome out = RenderAndDetect(DoorScene(32), Facing(32, 72.0, -6.0), camera);
  ExpectDoorFound(out, 32, 72.0);
}

TEST(RibbonDetectorRenderedTest, FindsDoorOpenInward) {
  const Outcome out =
      RenderAndDetect(DoorScene(36, DoorState::kOpenInward, 90.0), Facing(36, 72.0, 3.0));
  ExpectDoorFound(out, 36, 72.0);
}

TEST(RibbonDetectorRenderedTest, FindsDoorOpenOutward) {
  const Outcome out =
      RenderAndDetect(DoorScene(36, DoorState::kOpenOutward, 20.0), Facing(36, 96.0, 0.0));
  ExpectDoorFound(out, 36, 96.0);
}

TEST(RibbonDetectorRenderedTest, FindsDoubleDoorAtTwelveFeet) {
  const Outcome out = RenderAndDetect(DoorScene(72), Facing(72, 144.0, 0.0));
  ExpectDoorFound(out, 72, 144.0);
}

// At 5 ft a 36/36 is never whole in the 63 in view; its leaves are, each framed by its
// casing and the seam. Frames 6 in apart while one leaf is whole in view (a pinhole camera,
// so the seam's column is exact): with seam lines on, the leaf is among the two most
// confident pairs and scores as a face against both its casing and the seam; with every
// edge a step (the default) it scores under three quarters of that.
TEST(RibbonDetectorRenderedTest, FindsEachLeafOfADoubleDoorAtFiveFeet) {
  constexpr double kRangeIn = 60.0, kSeamIn = kDoorStartIn + 36.0;
  const Scene scene = DoorScene(72);
  CameraModel camera;
  camera.k1 = 0.0;
  const double f = camera.focal_px();
  RibbonDetectorParams seams;
  seams.seam_lines = true;
  for (const double x : {130.0, 136.0, 142.0, 172.0, 178.0, 184.0}) {
    SCOPED_TRACE("camera at x = " + std::to_string(x));
    const Pose2d X_WR{x, kHallwayWidthIn / 2.0 - kRangeIn, 0.0};
    const Outcome out = RenderAndDetect(scene, X_WR, camera, {}, seams);
    ASSERT_TRUE(out.result.ok()) << out.result.message;
    ASSERT_EQ(out.frame.truth.jambs.size(), 1u);  // one jamb of the opening in view
    const double jamb = out.frame.truth.jambs[0].column_px;
    const double seam = camera.cx_px() + f * (kSeamIn - x) / (kRangeIn + 1.0);  // leaves 1 in back
    const double left = std::min(jamb, seam), right = std::max(jamb, seam);
    const RibbonDetection& det = out.result.detection;
    const int k = MatchingPair(det, left, right);
    ASSERT_GE(k, 0) << "leaf " << left << ", " << right << "; " << Describe(det);
    EXPECT_LT(k, 2) << Describe(det);  // only the casing stripe may outrank it
    EXPECT_GT(det.pairs[k].confidence, 0.6) << Describe(det);
    const DetectResult before = RibbonDetector().Detect(out.frame.image, kRangeIn);
    const int kb = MatchingPair(before.detection, left, right);
    ASSERT_GE(kb, 0);
    EXPECT_LT(before.detection.pairs[kb].confidence, 0.75 * det.pairs[k].confidence);
  }
}

// A double door ajar has no seam: its leaves stand a few degrees into the room, and between
// their meeting stiles the room shows through, a gap only a little darker than the leaves.
// Seen by a camera rolled by a degree (the misalignment the realistic renders draw), the
// gap crosses the processed rows a pixel or two apart, and their mean level smears it. With
// seam lines on it is still read as a line where it is darkest, so each leaf, framed by its
// casing and the gap, is a candidate the landmark stage classifies (its min_confidence,
// 0.25 in configs/landmark.yaml). Read at the gap's mean level, the leaves scored 0.08-0.14.
TEST(RibbonDetectorRenderedTest, ReadsEachLeafOfADoubleDoorAjarByTheGapBetweenThem) {
  constexpr double kRangeIn = 60.0, kAjarDeg = 6.0, kMinConfidence = 0.25;
  HallwayOptions options;
  options.width_in = kHallwayWidthIn;
  const Scene scene(world::MakeStraightHallway(
      {HallwayFeature::Wall(kDoorStartIn),
       HallwayFeature::Door(72, DoorState::kOpenInward, DegToRad(kAjarDeg)),
       HallwayFeature::Wall(240)},
      options));
  CameraModel camera;
  camera.roll_deg = 1.0;
  RibbonDetectorParams seams;
  seams.seam_lines = true;
  const double leaf_px = camera.focal_px() * 36.0 / kRangeIn;
  // The optical axis on the first leaf, then on the second.
  for (const double x : {132.0, 138.0, 144.0, 168.0, 174.0, 180.0}) {
    SCOPED_TRACE("camera at x = " + std::to_string(x));
    const Outcome out =
        RenderAndDetect(scene, {x, kHallwayWidthIn / 2.0 - kRangeIn, 0.0}, camera, {}, seams);
    ASSERT_TRUE(out.result.ok()) << out.result.message;
    const RibbonDetection& det = out.result.detection;
    // The leaf in view: about 36 in wide at the range.
    const auto leaf = std::find_if(det.pairs.begin(), det.pairs.end(), [&](const CandidatePair& p) {
      return std::abs(p.width_px / leaf_px - 1.0) < 0.1;
    });
    ASSERT_NE(leaf, det.pairs.end()) << Describe(det);
    EXPECT_GE(leaf->confidence, kMinConfidence) << Describe(det);
  }
}

TEST(RibbonDetectorRenderedTest, FindsDoorUnderDimUnevenLight) {
  Illumination light;
  light.gain = 0.6;
  light.offset = 10.0;
  light.gradient = 0.4;
  light.noise_stddev = 3.0;
  const Outcome out = RenderAndDetect(DoorScene(40), Facing(40, 90.0, 2.0), {}, light);
  ExpectDoorFound(out, 40, 90.0);
}

TEST(RibbonDetectorRenderedTest, BlankWallGivesNoCandidatePair) {
  HallwayOptions options;
  options.width_in = kHallwayWidthIn;
  const Scene scene(world::MakeStraightHallway({HallwayFeature::Wall(600)}, options));
  for (double range_in : {48.0, 72.0, 144.0}) {
    const Outcome out = RenderAndDetect(scene, {300.0, kHallwayWidthIn / 2.0 - range_in, 0.0});
    ASSERT_TRUE(out.result.ok()) << out.result.message;
    EXPECT_TRUE(out.result.detection.pairs.empty())
        << "range " << range_in << ": " << Describe(out.result.detection);
  }
}

}  // namespace
}  // namespace stickrep::vision

namespace stickrep::vision {
namespace {

// A drive along a hallway inside the navigation envelope of §6.4.2 (within 1 ft of the
// axis, optical axis within 7.5° of the wall normal), one frame every 6.24 in (0.2 s at
// 2.6 ft/s). Every frame with a door fully in view (jambs 10 px or more inside the image)
// must yield its jamb pair within 2 px among the first five candidates in most frames.
TEST(RibbonDetectorRenderedTest, FindsMostDoorsAlongAnEnvelopeDrive) {
  std::mt19937_64 rng(kSeed);
  std::uniform_real_distribution<double> wall_len(48.0, 120.0);
  std::uniform_int_distribution<int> pick(0, 5);
  std::vector<HallwayFeature> features{HallwayFeature::Wall(120)};
  for (int i = 0; i < 8; ++i) {
    const int width = world::kDoorClassesIn[pick(rng)];
    const DoorState state = i % 4 == 3 ? DoorState::kOpenInward : DoorState::kClosed;
    features.push_back(HallwayFeature::Door(width, state, DegToRad(80.0)));
    features.push_back(i % 3 == 1 ? HallwayFeature::Poster(wall_len(rng))
                                  : HallwayFeature::Wall(wall_len(rng)));
  }
  HallwayOptions options;
  options.width_in = 144.0;  // 6 ft from the axis to each wall
  const Scene scene(world::MakeStraightHallway(features, options));
  const CameraRenderer renderer{CameraModel{}};
  const RibbonDetector detector;
  std::uniform_real_distribution<double> offset_in(-12.0, 12.0);
  std::uniform_real_distribution<double> yaw_rad(-DegToRad(7.5), DegToRad(7.5));

  int eligible = 0, found_top = 0, found_any = 0, frames = 0;
  const double length = world::HallwayLength(features);
  for (double x = 60.0; x < length - 60.0; x += 6.24) {
    const Pose2d X_WR{x, offset_in(rng), yaw_rad(rng)};
    const RenderedFrame frame = renderer.Render(scene, X_WR, {}, rng);
    const DetectResult result = detector.Detect(frame.image, frame.truth.axis_range_in);
    ASSERT_TRUE(result.ok()) << result.message;
    ++frames;
    for (const world::DoorTruth& door : frame.truth.doors) {
      if (!door.both_jambs_visible || door.left_column_px < 10.0 ||
          door.right_column_px > 512 - 10.0) {
        continue;
      }
      ++eligible;
      const int k = MatchingPair(result.detection, door.left_column_px, door.right_column_px);
      if (k >= 0) ++found_any;
      if (k >= 0 && k < kTopPairs) ++found_top;
    }
  }
  ::testing::Test::RecordProperty("frames", frames);
  ::testing::Test::RecordProperty("door_views", eligible);
  ::testing::Test::RecordProperty("found_in_top5", found_top);
  ::testing::Test::RecordProperty("found_anywhere", found_any);
  ASSERT_GT(eligible, 20);
  EXPECT_GE(static_cast<double>(found_top) / eligible, 0.8)
      << found_top << " of " << eligible << " door views (any rank: " << found_any << ")";
}

}  // namespace
}  // namespace stickrep::vision
