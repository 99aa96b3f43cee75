// The detector on cluttered renders: light strips between dark doors, posters,
// oblique narrow doors, full-frame clumping through floor reflections.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "common/units.h"
#include "vision/ribbon_detector.h"
#include "world/camera_renderer.h"
#include "world/realism.h"
#include "world/scene.h"
#include "world/world.h"

namespace stickrep::vision {
namespace {

using world::CameraModel;
using world::CameraRenderer;
using world::HallwayFeature;
using world::HallwayOptions;
using world::Pose2d;
using world::RenderedFrame;
using world::Scene;

constexpr std::uint64_t kSeed = 4242;
constexpr double kTolPx = 2.0;

HallwayOptions Hallway(double width_in) {
  HallwayOptions options;
  options.width_in = width_in;
  return options;
}

RenderedFrame Render(const Scene& scene, const Pose2d& X_WR, CameraModel camera = {}) {
  const CameraRenderer renderer(camera);
  std::mt19937_64 rng(kSeed);
  return renderer.Render(scene, X_WR, {}, rng);
}

std::string Describe(const RibbonDetection& det) {
  std::string s = "ground " + std::to_string(det.ground) + "; footprints:";
  for (const Footprint& f : det.footprints) {
    s += " " + std::to_string(f.column_px).substr(0, 6) + "(c" +
         std::to_string(f.contrast).substr(0, 4) + ",r" + std::to_string(f.rows_hit) + ")";
  }
  s += "; pairs:";
  for (size_t i = 0; i < det.pairs.size() && i < 8; ++i) {
    const CandidatePair& p = det.pairs[i];
    s += " [" + std::to_string(p.left_px).substr(0, 6) + "," +
         std::to_string(p.right_px).substr(0, 6) + " c" + std::to_string(p.confidence).substr(0, 5) +
         " i" + std::to_string(p.interior).substr(0, 5) + " l" +
         std::to_string(p.left_flank).substr(0, 5) + " r" +
         std::to_string(p.right_flank).substr(0, 5) + " f" +
         std::to_string(p.far_flank).substr(0, 5) + (p.ground_reversed ? " REV" : "") + "]";
  }
  return s;
}

bool PairOn(const CandidatePair& p, double left, double right) {
  return std::abs(p.left_px - left) <= kTolPx && std::abs(p.right_px - right) <= kTolPx;
}

// Two dark doors (leaf 60, casing 55) with a light panel (230) over the 24 in of wall
// between their casings, seen square-on from 12 ft: both doors whole in view.
TEST(RibbonDetectorRealismTest, ALightStripBetweenTwoDarkDoorsIsNotTheTopPair) {
  HallwayOptions options = Hallway(288.0);
  options.door_template.face_intensity = 60;
  options.door_template.frame_intensity = 55;
  world::World w = world::MakeStraightHallway(
      {HallwayFeature::Wall(200), HallwayFeature::Door(36), HallwayFeature::Wall(30),
       HallwayFeature::Door(36), HallwayFeature::Wall(200)},
      options);
  world::WallDecoration strip;
  strip.wall_index = 0;
  strip.offset_in = 239.0;  // door 0 ends at 236 + 3 in of casing; door 1's casing at 263
  strip.width_in = 24.0;
  strip.bottom_in = 4.0;
  strip.top_in = 96.0;
  strip.intensity = 230;
  w.decorations.push_back(strip);
  const Scene scene(w);
  const RenderedFrame frame = Render(scene, {251.0, 0.0, 0.0});
  ASSERT_EQ(frame.truth.doors.size(), 2u);
  // With the widths a legal door (up to 72 in plus casings) can have at this range, as the
  // landmark pipeline gives them: the pair round both doors and the strip goes.
  const double f = CameraModel{}.focal_px();
  const double range = frame.truth.axis_range_in;
  const DetectResult r =
      RibbonDetector().Detect(frame.image, range, PairWidthLimits{8.0, 1.15 * f * 84.0 / range});
  ASSERT_TRUE(r.ok());
  ASSERT_FALSE(r.detection.pairs.empty());
  const CandidatePair& top = r.detection.pairs.front();
  // The strip: its edges are the doors' outer casing edges, 24 in apart.
  const double centre = 0.5 * (top.left_px + top.right_px);
  EXPECT_FALSE(std::abs(centre - 255.5) < 10.0 && top.interior > top.left_flank)
      << "top pair " << top.left_px << ".." << top.right_px << " interior " << top.interior;
  // It lies on one of the doors (casing included).
  bool on_door = false;
  for (const world::DoorTruth& d : frame.truth.doors) {
    on_door |= centre > d.left_column_px && centre < d.right_column_px;
  }
  EXPECT_TRUE(on_door) << Describe(r.detection);
  EXPECT_GE(r.detection.ground, 0.0);
  // The strip pair, if offered, is marked as the ground between figures.
  for (const CandidatePair& p : r.detection.pairs) {
    if (std::abs(0.5 * (p.left_px + p.right_px) - 255.5) < 6.0 && p.interior > 200.0) {
      EXPECT_TRUE(p.ground_reversed);
    }
  }
}

// A door-free wall with a glazed notice board and a dark poster, against a plain closed
// door, both at 6 ft: confidences are absolute, so the clutter stays below the door.
TEST(RibbonDetectorRealismTest, PosterFrameConfidenceStaysBelowADoors) {
  world::World posters =
      world::MakeStraightHallway({HallwayFeature::Wall(600)}, Hallway(144.0));
  for (const auto& [at, width, grey, layer] :
       {std::tuple{270.0, 32.0, 50, 0}, std::tuple{271.5, 29.0, 240, 1},
        std::tuple{320.0, 24.0, 45, 0}}) {
    world::WallDecoration d;
    d.offset_in = at;
    d.width_in = width;
    d.bottom_in = 38.0;
    d.top_in = 70.0;
    d.intensity = grey;
    d.layer = layer;
    posters.decorations.push_back(d);
  }
  const RenderedFrame clutter = Render(Scene(posters), {300.0, 0.0, 0.0});
  const Scene door_scene(world::MakeStraightHallway(
      {HallwayFeature::Wall(200), HallwayFeature::Door(36), HallwayFeature::Wall(200)},
      Hallway(144.0)));
  const RenderedFrame door = Render(door_scene, {218.0, 0.0, 0.0});
  const RibbonDetector detector;
  const DetectResult rc = detector.Detect(clutter.image, clutter.truth.axis_range_in);
  const DetectResult rd = detector.Detect(door.image, door.truth.axis_range_in);
  ASSERT_TRUE(rc.ok() && rd.ok());
  ASSERT_FALSE(rd.detection.pairs.empty());
  // The door's confidence: its jamb pair, or the pair round its casing if that is higher
  // (the casing rule hands the opening the group's confidence).
  const world::DoorTruth& truth = door.truth.doors.at(0);
  const double casing_px = truth.right_column_px - truth.left_column_px;
  double door_conf = -1.0;
  for (const CandidatePair& p : rd.detection.pairs) {
    const bool opening = PairOn(p, truth.left_column_px, truth.right_column_px);
    const bool casing = p.left_px < truth.left_column_px && p.right_px > truth.right_column_px &&
                        p.width_px < casing_px * 42.0 / 36.0 + 2.0 * kTolPx;
    if (opening || casing) door_conf = std::max(door_conf, p.confidence);
  }
  ASSERT_GT(door_conf, 0.0);
  double clutter_conf = 0.0;
  for (const CandidatePair& p : rc.detection.pairs) clutter_conf = std::max(clutter_conf, p.confidence);
  EXPECT_LT(clutter_conf, 0.75 * door_conf)
      << Describe(rc.detection) << "\n door: " << Describe(rd.detection);
}

// A 30 in door seen 75° off the wall normal from 6 ft: about 13 px wide. Still paired.
TEST(RibbonDetectorRealismTest, AnObliqueNarrowDoorIsStillPaired) {
  const Scene scene(world::MakeStraightHallway(
      {HallwayFeature::Wall(400), HallwayFeature::Door(30), HallwayFeature::Wall(400)},
      Hallway(144.0)));
  // Camera on the axis (72 in from the wall), its axis 75° from the wall normal, meeting
  // the wall at the door's centre.
  const double theta = DegToRad(75.0);
  const double along = 72.0 * std::tan(theta);
  // The camera looks 90° left of the heading: a heading of -theta turns it theta toward +x.
  const Pose2d X_WR{415.0 - along, 0.0, -theta};
  const RenderedFrame frame = Render(scene, X_WR);
  ASSERT_EQ(frame.truth.doors.size(), 1u);
  const world::DoorTruth& d = frame.truth.doors[0];
  ASSERT_TRUE(d.both_jambs_visible);
  const double width = d.right_column_px - d.left_column_px;
  ASSERT_GT(width, 10.0);
  ASSERT_LT(width, 18.0);
  const DetectResult r = RibbonDetector().Detect(frame.image, frame.truth.axis_range_in);
  ASSERT_TRUE(r.ok());
  bool found = false;
  for (const CandidatePair& p : r.detection.pairs) {
    found |= PairOn(p, d.left_column_px, d.right_column_px);
  }
  EXPECT_TRUE(found) << "truth " << d.left_column_px << ".." << d.right_column_px;
}

TEST(RibbonDetectorRealismTest, PairsOutsideTheGivenWidthLimitsAreNotOffered) {
  const Scene scene(world::MakeStraightHallway(
      {HallwayFeature::Wall(200), HallwayFeature::Door(36), HallwayFeature::Wall(200)},
      Hallway(144.0)));
  const RenderedFrame frame = Render(scene, {218.0, 0.0, 0.0});
  const RibbonDetector detector;
  const DetectResult open = detector.Detect(frame.image, 72.0);
  ASSERT_TRUE(open.ok());
  double widest = 0.0;
  for (const CandidatePair& p : open.detection.pairs) widest = std::max(widest, p.width_px);
  ASSERT_GT(widest, 150.0) << Describe(open.detection);
  // The opening (36 in, about 244 px) stays; the casing pair (42 in) and the bands go.
  const DetectResult gated = detector.Detect(frame.image, 72.0, PairWidthLimits{200.0, 260.0});
  ASSERT_TRUE(gated.ok());
  ASSERT_FALSE(gated.detection.pairs.empty());
  for (const CandidatePair& p : gated.detection.pairs) {
    EXPECT_GE(p.width_px, 200.0);
    EXPECT_LE(p.width_px, 260.0);
  }
}

// Full-frame mode on a glossy floor with baseboards: the reflections and the baseboard's
// top edge cross many rows, and clumps must not grow past max_clump_width_px.
TEST(RibbonDetectorRealismTest, FullFrameClumpsStayBoundedOnAGlossyFloor) {
  world::RealismOptions o = world::CleanRender();
  o.floor_reflections = true;
  o.ceiling_lights = true;
  o.door_appearance = true;
  o.dark_door_share = 1.0;
  o.white_door_share = 0.0;
  world::World w = world::MakeStraightHallway(
      {HallwayFeature::Wall(200), HallwayFeature::Door(36), HallwayFeature::Wall(14),
       HallwayFeature::Door(36), HallwayFeature::Wall(200)},
      Hallway(144.0));
  std::mt19937_64 rng(kSeed);
  world::ApplyRealism(o, rng, &w);
  const Pose2d X_WR{250.0, 20.0, DegToRad(-20.0)};
  const RenderedFrame frame = Render(Scene(w), X_WR);
  RibbonDetectorParams params;
  params.row_mode = RowMode::kFullFrame;
  const DetectResult r = RibbonDetector(params).Detect(frame.image, 72.0);
  ASSERT_TRUE(r.ok());
  ASSERT_FALSE(r.detection.footprints.empty());
  for (const Footprint& f : r.detection.footprints) {
    EXPECT_LE(f.last_bin - f.first_bin + 1, params.max_clump_width_px);
  }
}

}  // namespace
}  // namespace stickrep::vision
