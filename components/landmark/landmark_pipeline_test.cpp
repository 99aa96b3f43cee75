// The landmark pipeline (detector, casing rule, Short Side geometry, Bayes classes) on
// frames drawn by the simulated world, and the casing rule on hand-made detections.
#include "landmark/landmark_pipeline.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "common/units.h"
#include "sensing/robot_config.h"
#include "world/camera_renderer.h"
#include "world/robot_models.h"
#include "world/scene.h"
#include "world/sonar_ring.h"
#include "world/world.h"

namespace stickrep::landmark {
namespace {

using sensing::DoorClass;
using world::DoorState;
using world::HallwayFeature;

constexpr double kDoorStartIn = 120.0;
constexpr double kHallwayWidthIn = 240.0;  // room to stand 12 ft from the feature wall
constexpr std::uint64_t kSeed = 1234;
constexpr double kJambTolerancePx = 2.0;

world::Scene DoorScene(double width_in, DoorState state = DoorState::kClosed,
                       double angle_deg = 0.0) {
  world::HallwayOptions options;
  options.width_in = kHallwayWidthIn;
  return world::Scene(world::MakeStraightHallway(
      {HallwayFeature::Wall(kDoorStartIn),
       HallwayFeature::Door(width_in, state, DegToRad(angle_deg)), HallwayFeature::Wall(240)},
      options));
}

// Robot heading +x, camera looking at the feature wall from range_in, the optical axis
// meeting the wall along_in past the door centre.
world::Pose2d Facing(double width_in, double range_in, double along_in = 0.0) {
  return {kDoorStartIn + width_in / 2.0 + along_in, kHallwayWidthIn / 2.0 - range_in, 0.0};
}

struct Frame {
  world::RenderedFrame rendered;
  sensing::SonarScan scan;
  vision::ImageView view() const {
    const cv::Mat& img = rendered.image;
    return {img.cols, img.rows, static_cast<int>(img.step), "mono8", img.data, img.total()};
  }
};

// One frame and the exact sonar sweep from the same pose, both from the robot description
// of configs/robot.yaml (its defaults).
Frame Render(const world::Scene& scene, const world::Pose2d& X_WR, double roll_deg = 0.0) {
  world::RobotModels models = world::RobotModelsFromConfig(sensing::RobotConfig{});
  models.camera.roll_deg = roll_deg;
  const world::CameraRenderer renderer(models.camera);
  const world::SonarRingSimulator ring(models.sonar);
  std::mt19937_64 rng(kSeed);
  Frame out;
  out.rendered = renderer.Render(scene, X_WR, world::Illumination{}, rng);
  for (const world::SonarReading& r : ring.SenseExact(scene, X_WR)) {
    out.scan.ranges_in.push_back(r.valid ? r.range_in : 0.0);
    out.scan.valid.push_back(r.valid);
  }
  return out;
}

FrameOutcome ProcessWith(const Frame& frame, const vision::RibbonDetectorParams& detector,
                         CasingRule rule = {}) {
  const LandmarkPipeline pipeline(sensing::RobotConfig{}, detector,
                                  sensing::LandmarkEstimatorConfig{}, rule);
  return pipeline.Process(frame.view(), frame.scan);
}

FrameOutcome Process(const Frame& frame, CasingRule rule = {}) {
  return ProcessWith(frame, vision::RibbonDetectorParams{}, rule);
}

// The observation is of the door's jambs (not its casing) and of the given class.
void ExpectJambsClassified(const Frame& frame, const FrameOutcome& out, DoorClass expected) {
  ASSERT_EQ(out.kind, FrameOutcome::Kind::kObservation) << out.reason;
  ASSERT_EQ(frame.rendered.truth.doors.size(), 1u);
  const world::DoorTruth& door = frame.rendered.truth.doors[0];
  EXPECT_NEAR(out.observation.footprints.lj_px, door.left_column_px, kJambTolerancePx);
  EXPECT_NEAR(out.observation.footprints.rj_px, door.right_column_px, kJambTolerancePx);
  EXPECT_EQ(out.observation.door_class, expected)
      << "class " << sensing::ToString(out.observation.door_class) << ", width "
      << out.observation.width_in << " in";
  ::testing::Test::RecordProperty("width_in", std::to_string(out.observation.width_in));
}

TEST(LandmarkPipelineTest, Classifies36InDoorAtSixFeetBy36NotByItsCasing) {
  const Frame frame = Render(DoorScene(36), Facing(36, 72.0, 4.3));
  const FrameOutcome out = Process(frame);
  ExpectJambsClassified(frame, out, DoorClass::k36);
  EXPECT_EQ(out.casings, 1);
}

TEST(LandmarkPipelineTest, ReadsTheLeafMarkBetweenTheJambsItFound) {
  // Table 6.8's marks on a closed 36 in leaf, from the jambs the detector found at 6 and 8 ft.
  const std::pair<world::DoorPattern, map::DoorMark> cases[] = {
      {world::DoorPattern::kNone, map::DoorMark::kPlain},
      {world::DoorPattern::kWindow, map::DoorMark::kWindow},
      {world::DoorPattern::kPoster, map::DoorMark::kPoster}};
  for (const auto& [pattern, mark] : cases) {
    HallwayFeature door = HallwayFeature::Door(36);
    door.pattern = pattern;
    world::HallwayOptions options;
    options.width_in = kHallwayWidthIn;
    const world::Scene scene(world::MakeStraightHallway(
        {HallwayFeature::Wall(kDoorStartIn), door, HallwayFeature::Wall(240)}, options));
    for (const double range_in : {72.0, 96.0}) {
      const Frame frame = Render(scene, Facing(36, range_in, 2.0));
      const FrameOutcome out = Process(frame);
      ExpectJambsClassified(frame, out, DoorClass::k36);
      EXPECT_EQ(out.mark.mark, mark) << map::DoorMarkName(out.mark.mark) << " at " << range_in
                                     << " in, share " << out.mark.mark_share << ", "
                                     << out.mark.why_unknown;
    }
  }
}

TEST(LandmarkPipelineTest, Classifies30InDoorAtEightFeetBy30WhereItsCasingReads36) {
  // At 6 ft the 30 in door reads 31.4 in, on the 30|32 boundary: the width bias of the
  // pipeline (docs/measured_error_model.md), not the casing.
  const Frame frame = Render(DoorScene(30), Facing(30, 96.0, -3.0));
  ExpectJambsClassified(frame, Process(frame), DoorClass::k30);
  // Without the rule, and without the detector's one-face rule, the most confident pair
  // is the casing: 30 + 2 x 3 in, class 36.
  CasingRule off;
  off.enabled = false;
  vision::RibbonDetectorParams any_face;
  any_face.two_faces_factor = 1.0;
  const FrameOutcome without = ProcessWith(frame, any_face, off);
  ASSERT_EQ(without.kind, FrameOutcome::Kind::kObservation) << without.reason;
  EXPECT_EQ(without.observation.door_class, DoorClass::k36);
  // The one-face rule alone marks the casing pair down (its casing-to-opening edges step
  // between two faces inside it): the opening is classified even without the casing rule.
  const FrameOutcome one_face = Process(frame, off);
  ASSERT_EQ(one_face.kind, FrameOutcome::Kind::kObservation) << one_face.reason;
  EXPECT_EQ(one_face.observation.door_class, DoorClass::k30);
}

TEST(LandmarkPipelineTest, Classifies32InDoorAtEightFeetBy32WhereItsCasingReads40) {
  const Frame frame = Render(DoorScene(32), Facing(32, 96.0, 0.0));
  ExpectJambsClassified(frame, Process(frame), DoorClass::k32);
  CasingRule off;
  off.enabled = false;
  vision::RibbonDetectorParams any_face;
  any_face.two_faces_factor = 1.0;
  const FrameOutcome without = ProcessWith(frame, any_face, off);
  ASSERT_EQ(without.kind, FrameOutcome::Kind::kObservation) << without.reason;
  EXPECT_EQ(without.observation.door_class, DoorClass::k40);
}

TEST(LandmarkPipelineTest, Classifies36InDoorAtTwelveFeet) {
  const Frame frame = Render(DoorScene(36), Facing(36, 144.0, -20.0));
  ExpectJambsClassified(frame, Process(frame), DoorClass::k36);
}

TEST(LandmarkPipelineTest, BlankWallGivesNoDoor) {
  world::HallwayOptions options;
  options.width_in = kHallwayWidthIn;
  const world::Scene scene(world::MakeStraightHallway({HallwayFeature::Wall(600)}, options));
  for (double range_in : {48.0, 72.0, 144.0}) {
    const FrameOutcome out = Process(Render(scene, {300.0, kHallwayWidthIn / 2.0 - range_in, 0.0}));
    EXPECT_EQ(out.kind, FrameOutcome::Kind::kNoDoor) << "range " << range_in;
    EXPECT_EQ(out.candidates, 0) << "range " << range_in;
  }
}

TEST(LandmarkPipelineTest, ToleratesTenDegreesOfRollAtTwelveFeet) {
  // §4.1.1: "misalignment angle as great as 10 degrees from vertical at a distance of 12 feet".
  const Frame frame = Render(DoorScene(36), Facing(36, 144.0, 10.0), 10.0);
  ExpectJambsClassified(frame, Process(frame), DoorClass::k36);
}

TEST(LandmarkPipelineTest, ToleratesTenDegreesOfRollAtSixFeet) {
  const Frame frame = Render(DoorScene(36), Facing(36, 72.0, -4.0), -10.0);
  ExpectJambsClassified(frame, Process(frame), DoorClass::k36);
}

TEST(LandmarkPipelineTest, ClassifiesDoorOpenIntoTheRoom) {
  const Frame frame = Render(DoorScene(36, DoorState::kOpenInward, 90.0), Facing(36, 72.0, 3.0));
  ExpectJambsClassified(frame, Process(frame), DoorClass::k36);
}

TEST(LandmarkPipelineTest, ClassifiesDoorOpenIntoTheHallway) {
  const Frame frame = Render(DoorScene(36, DoorState::kOpenOutward, 20.0), Facing(36, 96.0, 0.0));
  const FrameOutcome out = Process(frame);
  ExpectJambsClassified(frame, out, DoorClass::k36);
}

TEST(LandmarkPipelineTest, ClassifiesDoubleDoorByItsOpeningNotItsHalves) {
  const Frame frame = Render(DoorScene(72), Facing(72, 144.0, 0.0));
  ExpectJambsClassified(frame, Process(frame), DoorClass::k36_36);
}

TEST(LandmarkPipelineTest, FrameWithoutCoaxialRangeIsDropped) {
  Frame frame = Render(DoorScene(36), Facing(36, 72.0));
  frame.scan.valid[0] = false;
  EXPECT_EQ(Process(frame).kind, FrameOutcome::Kind::kNoRange);
  frame.scan.valid.clear();
  EXPECT_EQ(Process(frame).kind, FrameOutcome::Kind::kNoRange);
}

TEST(LandmarkPipelineTest, UnreadableFrameIsDropped) {
  const Frame frame = Render(DoorScene(36), Facing(36, 72.0));
  vision::ImageView view = frame.view();
  view.size_bytes -= 1;
  const LandmarkPipeline pipeline(sensing::RobotConfig{}, {}, {});
  EXPECT_EQ(pipeline.Process(view, frame.scan).kind, FrameOutcome::Kind::kBadFrame);
}

// Hand-made detections for the casing rule.
vision::Footprint Fp(double column_px, int polarity, double weight = 0.25) {
  vision::Footprint f;
  f.column_px = column_px;
  f.polarity = polarity;
  f.weight = weight;
  f.rows_hit = 5;
  return f;
}

// Every pair of footprints, confidence sqrt(w_l w_r), halved for like polarity, highest
// first (the detector's step (5)).
vision::RibbonDetection AllPairs(std::vector<vision::Footprint> fps) {
  vision::RibbonDetection det;
  det.footprints = std::move(fps);
  for (int l = 0; l < static_cast<int>(det.footprints.size()); ++l) {
    for (int r = l + 1; r < static_cast<int>(det.footprints.size()); ++r) {
      vision::CandidatePair p;
      p.left_index = l;
      p.right_index = r;
      p.left_px = det.footprints[l].column_px;
      p.right_px = det.footprints[r].column_px;
      p.width_px = p.right_px - p.left_px;
      p.confidence = std::sqrt(det.footprints[l].weight * det.footprints[r].weight) *
                     (det.footprints[l].polarity == det.footprints[r].polarity ? 0.5 : 1.0);
      det.pairs.push_back(p);
    }
  }
  std::stable_sort(det.pairs.begin(), det.pairs.end(),
                   [](const auto& a, const auto& b) { return a.confidence > b.confidence; });
  return det;
}

TEST(CasingRuleTest, KeepsTheOpeningOfAFramedDoorWithTheGroupsConfidence) {
  // Wall -> dark casing -> leaf -> casing -> wall: the outer edges are the stronger.
  const auto det =
      AllPairs({Fp(100, -1, 0.3), Fp(120, +1, 0.2), Fp(360, -1, 0.2), Fp(380, +1, 0.3)});
  int casings = 0;
  const auto out = CandidatesAfterCasingRule(det, CasingRule{}, &casings);
  EXPECT_EQ(casings, 1);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_DOUBLE_EQ(out[0].footprints.lj_px, 120.0);
  EXPECT_DOUBLE_EQ(out[0].footprints.rj_px, 360.0);
  EXPECT_NEAR(out[0].confidence, 0.3, 1e-12);
}

TEST(CasingRuleTest, LeavesTwoDoorsSideBySideAlone) {
  // Two 36 in doors 12 in apart: the "bands" would be whole doors.
  const auto det = AllPairs({Fp(50, -1), Fp(200, +1), Fp(260, -1), Fp(410, +1)});
  int casings = 0;
  EXPECT_EQ(CandidatesAfterCasingRule(det, CasingRule{}, &casings).size(), det.pairs.size());
  EXPECT_EQ(casings, 0);
}

TEST(CasingRuleTest, NeedsStripesOfOppositePolarityOnBothSides) {
  // A step on the left (both edges darkening) is not a casing band.
  const auto det = AllPairs({Fp(100, -1), Fp(120, -1), Fp(360, -1), Fp(380, +1)});
  int casings = 0;
  EXPECT_EQ(CandidatesAfterCasingRule(det, CasingRule{}, &casings).size(), det.pairs.size());
  EXPECT_EQ(casings, 0);
}

TEST(CasingRuleTest, NeedsBandsOfLikeWidth) {
  const auto det = AllPairs({Fp(100, -1), Fp(110, +1), Fp(340, -1), Fp(380, +1)});
  int casings = 0;
  CandidatesAfterCasingRule(det, CasingRule{}, &casings);
  EXPECT_EQ(casings, 0);
}

TEST(CasingRuleTest, EdgesSeenInOneRowOnlyDoNotFrameACasing) {
  // A rolled jamb crosses an outer row far from where the centre rows see it: those
  // one-row strays beside a jamb look like a band but are not a casing.
  std::vector<vision::Footprint> fps = {Fp(100, -1), Fp(120, +1), Fp(360, -1), Fp(380, +1)};
  fps[0].rows_hit = 1;
  int casings = 0;
  const auto det = AllPairs(fps);
  EXPECT_EQ(CandidatesAfterCasingRule(det, CasingRule{}, &casings).size(), det.pairs.size());
  EXPECT_EQ(casings, 0);
}

TEST(CasingRuleTest, DisabledRuleKeepsEveryPair) {
  const auto det = AllPairs({Fp(100, -1), Fp(120, +1), Fp(360, -1), Fp(380, +1)});
  CasingRule off;
  off.enabled = false;
  EXPECT_EQ(CandidatesAfterCasingRule(det, off).size(), det.pairs.size());
}

TEST(CasingRuleTest, WithdrawsPairsFromTheCasingToADoubleDoorSeam) {
  // A double door: the dark seam between the leaves is one darkening footprint.
  const auto det = AllPairs({Fp(100, -1, 0.24), Fp(116, +1, 0.14), Fp(255, -1, 0.24),
                             Fp(409, -1, 0.14), Fp(424, +1, 0.24)});
  const auto out = CandidatesAfterCasingRule(det, CasingRule{});
  ASSERT_FALSE(out.empty());
  const auto best = std::max_element(out.begin(), out.end(), [](const auto& a, const auto& b) {
    return a.confidence < b.confidence;
  });
  EXPECT_DOUBLE_EQ(best->footprints.lj_px, 116.0);
  EXPECT_DOUBLE_EQ(best->footprints.rj_px, 409.0);
  for (const auto& c : out) {
    EXPECT_FALSE(c.footprints.lj_px == 100.0 || c.footprints.rj_px == 424.0)
        << c.footprints.lj_px << ", " << c.footprints.rj_px;
  }
}

}  // namespace
}  // namespace stickrep::landmark

namespace stickrep::landmark {
namespace {

sensing::CameraModel DefaultCamera() {
  return sensing::CameraModel::FromConfig(sensing::RobotConfig{}.camera);
}

TEST(LegalPairWidthsTest, SquareOnTheLimitsBracketThePinholeWidths) {
  const sensing::CameraModel cam = DefaultCamera();
  WidthGate gate;
  const vision::PairWidthLimits l = LegalPairWidths(cam, 72.0, 0.0, 28.5, 48.0, gate);
  const double f = 1.0 / cam.pitch_over_focal;
  // A 28.5 in door at 72 in is 28.5 / 72 f px square-on; at a farther range (+15 %) or
  // turned 7.5° it looks narrower. A 48 in one looks widest at the near side of the view.
  EXPECT_LT(l.min_px, f * 28.5 / 72.0);
  EXPECT_GT(l.min_px, 0.7 * f * 28.5 / 72.0);
  EXPECT_GT(l.max_px, f * 48.0 / 72.0);
  EXPECT_LT(l.max_px, 1.5 * f * 48.0 / 72.0);
}

TEST(LegalPairWidthsTest, ObliqueStaresAdmitNarrowerDoors) {
  const sensing::CameraModel cam = DefaultCamera();
  const WidthGate gate;
  const vision::PairWidthLimits square = LegalPairWidths(cam, 72.0, 0.0, 28.5, 84.0, gate);
  const vision::PairWidthLimits oblique =
      LegalPairWidths(cam, 72.0, DegToRad(45.0), 28.5, 84.0, gate);
  EXPECT_LT(oblique.min_px, 0.75 * square.min_px);
}

// A frame whose sonar says the wall is 20 ft away: a pair 400 px wide is no legal door
// there (84 in at 240 in is about 170 px) and the pipeline does not offer it.
TEST(LandmarkPipelineTest, APairWiderThanAnyLegalClassAtTheRangeIsPruned) {
  cv::Mat img(480, 512, CV_8UC1, cv::Scalar(180));
  img.colRange(56, 456).setTo(60);  // a dark face 400 px wide on a light wall
  const vision::ImageView view{img.cols, img.rows, static_cast<int>(img.step), "mono8",
                               img.data, img.total()};
  sensing::SonarScan scan;
  for (int k = 0; k < 24; ++k) {
    scan.ranges_in.push_back(232.5);  // 240 in from the ring centre
    scan.valid.push_back(true);
  }
  const LandmarkPipeline gated(sensing::RobotConfig{}, vision::RibbonDetectorParams{},
                               sensing::LandmarkEstimatorConfig{});
  WidthGate off;
  off.enabled = false;
  const LandmarkPipeline open(sensing::RobotConfig{}, vision::RibbonDetectorParams{},
                              sensing::LandmarkEstimatorConfig{}, CasingRule{}, off);
  const FrameOutcome with = gated.Process(view, scan);
  const FrameOutcome without = open.Process(view, scan);
  EXPECT_LT(with.width_limits.max_px, 250.0);
  EXPECT_EQ(with.candidates, 0);
  ASSERT_EQ(without.candidates, 1);
  EXPECT_NEAR(without.ranked.at(0).footprints.rj_px - without.ranked.at(0).footprints.lj_px,
              400.0, 2.0);
}

}  // namespace
}  // namespace stickrep::landmark
