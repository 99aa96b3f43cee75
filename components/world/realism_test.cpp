#include "world/realism.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "common/units.h"
#include "world/camera_renderer.h"
#include "world/scene.h"

namespace stickrep::world {
namespace {

constexpr double kHallwayWidthIn = 288.0;  // the wall 12 ft from the camera on the axis
constexpr std::uint64_t kSeed = 1717;

// A wall with two doors 30 in apart (casing to casing 24 in) and a long plain stretch.
World TwoDoors() {
  HallwayOptions options;
  options.width_in = kHallwayWidthIn;
  return MakeStraightHallway({HallwayFeature::Wall(120), HallwayFeature::Door(36),
                              HallwayFeature::Wall(30), HallwayFeature::Door(36),
                              HallwayFeature::Wall(400)},
                             options);
}

// Many doors with long walls between them, for the drawn shares.
World ManyDoors(int doors) {
  std::vector<HallwayFeature> f;
  for (int k = 0; k < doors; ++k) {
    f.push_back(HallwayFeature::Wall(100));
    f.push_back(HallwayFeature::Door(36));
  }
  f.push_back(HallwayFeature::Wall(100));
  HallwayOptions options;
  options.width_in = kHallwayWidthIn;
  return MakeStraightHallway(f, options);
}

World Applied(World world, const RealismOptions& o, std::uint64_t seed = kSeed) {
  std::mt19937_64 rng(seed);
  ApplyRealism(o, rng, &world);
  return world;
}

RealismOptions Only(bool RealismOptions::*feature) {
  RealismOptions o = CleanRender();
  o.*feature = true;
  return o;
}

Illumination NoNoise() {
  Illumination light;
  light.noise_stddev = 0.0;
  return light;
}

// Rendered frame of `world` from the hallway axis looking at the feature wall, centred at x.
cv::Mat RenderAt(const World& world, double x_in, CameraModel camera = {}) {
  camera.k1 = 0.0;
  const CameraRenderer renderer(camera);
  std::mt19937_64 rng(3);
  return renderer.Render(Scene(world), {x_in, 0.0, 0.0}, NoNoise(), rng).image;
}

int CountKind(const Scene& scene, PanelKind kind) {
  return static_cast<int>(std::count_if(scene.panels().begin(), scene.panels().end(),
                                        [&](const Panel& p) { return p.kind == kind; }));
}

TEST(RealismTest, BaseboardsAreDrawnWhenOnAndAbsentWhenOff) {
  RealismOptions on = CleanRender();
  on.baseboard_height_in = 6.0;
  const Scene with(Applied(TwoDoors(), on));
  RealismOptions off = CleanRender();
  off.baseboards = false;
  const Scene without(Applied(TwoDoors(), off));
  EXPECT_GT(CountKind(with, PanelKind::kBaseboard), 0);
  EXPECT_EQ(CountKind(without, PanelKind::kBaseboard), 0);
  for (const Panel& p : with.panels()) {
    if (p.kind == PanelKind::kBaseboard) {
      EXPECT_DOUBLE_EQ(p.top_in, 6.0);
    }
  }
}

TEST(RealismTest, FloorReflectionMirrorsADarkDoorBelowTheWall) {
  RealismOptions looks = Only(&RealismOptions::door_appearance);
  looks.dark_door_share = 1.0;
  looks.white_door_share = 0.0;
  const World dark = Applied(TwoDoors(), looks);
  RealismOptions glossy = looks;
  glossy.floor_reflections = true;
  const World mirrored = Applied(TwoDoors(), glossy);
  // Door 0 spans x 120-156; the camera centred on it sees the floor below row ~400.
  const cv::Mat matte = RenderAt(dark, 138.0);
  const cv::Mat shiny = RenderAt(mirrored, 138.0);
  const int row = 470, door_col = 255, wall_col = 40;
  // Matte: the floor is one shade under the door and under the wall.
  EXPECT_EQ(matte.at<std::uint8_t>(row, door_col), matte.at<std::uint8_t>(row, wall_col));
  // Glossy: the dark door shows in the floor below it, darker than the wall's reflection.
  EXPECT_LT(shiny.at<std::uint8_t>(row, door_col) + 10, shiny.at<std::uint8_t>(row, wall_col));
}

TEST(RealismTest, CeilingLightsAreBrightStripsAtTheTopOfTheFrame) {
  const cv::Mat plain = RenderAt(Applied(TwoDoors(), CleanRender()), 300.0);
  const cv::Mat lit = RenderAt(Applied(TwoDoors(), Only(&RealismOptions::ceiling_lights)), 300.0);
  const cv::Mat top_plain = plain.rowRange(0, 40), top_lit = lit.rowRange(0, 40);
  double max_plain = 0.0, max_lit = 0.0;
  cv::minMaxLoc(top_plain, nullptr, &max_plain);
  cv::minMaxLoc(top_lit, nullptr, &max_lit);
  EXPECT_LT(max_plain, 220.0);
  EXPECT_GE(max_lit, 240.0);
  EXPECT_TRUE(Applied(TwoDoors(), CleanRender()).ceiling_lights.empty());
}

TEST(RealismTest, NoticeBoardsAre20To40InchesWideAndSomeGlazed) {
  RealismOptions o = Only(&RealismOptions::notice_boards);
  const World w = Applied(ManyDoors(60), o);
  int boards = 0, panes = 0;
  for (const WallDecoration& d : w.decorations) {
    if (d.layer == 1) {
      ++panes;
      continue;
    }
    ++boards;
    EXPECT_GE(d.width_in, 20.0);
    EXPECT_LE(d.width_in, 40.0);
    EXPECT_GT(std::abs(d.intensity - w.walls[d.wall_index].intensity), 30);
  }
  EXPECT_GT(boards, 20);
  EXPECT_GT(panes, 5);
  EXPECT_LT(panes, boards);
  EXPECT_TRUE(Applied(ManyDoors(60), CleanRender()).decorations.empty());
}

TEST(RealismTest, PilastersAreLightStripsBetweenDarkDoors) {
  const World w = Applied(TwoDoors(), Only(&RealismOptions::pilasters));
  ASSERT_EQ(w.decorations.size(), 1u);
  const WallDecoration& strip = w.decorations[0];
  const int wall = w.walls[strip.wall_index].intensity;
  EXPECT_GT(strip.intensity, wall + 20);
  // Between the casings: door 0 ends at 156 + 3, door 1 starts at 186 - 3.
  EXPECT_GE(strip.offset_in, 159.0 - 1e-9);
  EXPECT_LE(strip.offset_in + strip.width_in, 183.0 + 1e-9);
  for (const DoorFeature& d : w.doors) EXPECT_LE(d.face_intensity, 80);
  // Doors far apart get none.
  EXPECT_TRUE(Applied(ManyDoors(5), Only(&RealismOptions::pilasters)).decorations.empty());
}

TEST(RealismTest, DoorLooksFollowTheirShares) {
  const World w = Applied(ManyDoors(400), Only(&RealismOptions::door_appearance));
  int dark = 0, white = 0;
  for (const DoorFeature& d : w.doors) {
    const int wall = w.walls[d.wall_index].intensity;
    if (d.face_intensity <= 80) ++dark;
    if (std::abs(d.face_intensity - wall) <= 8) {
      ++white;
      EXPECT_LT(d.frame_intensity, wall - 10);  // only the casing shows
    }
  }
  EXPECT_NEAR(dark / 400.0, 0.4, 0.07);
  EXPECT_NEAR(white / 400.0, 0.2, 0.06);
}

TEST(RealismTest, SomeClosedDoorsStandAjarByAFewDegrees) {
  const World w = Applied(ManyDoors(400), Only(&RealismOptions::doors_ajar));
  int ajar = 0;
  for (const DoorFeature& d : w.doors) {
    if (d.state == DoorState::kClosed) continue;
    ++ajar;
    EXPECT_GE(d.open_angle_rad, DegToRad(2.0) - 1e-12);
    EXPECT_LE(d.open_angle_rad, DegToRad(12.0) + 1e-12);
  }
  EXPECT_NEAR(ajar / 400.0, 0.2, 0.06);
  for (const DoorFeature& d : Applied(ManyDoors(50), CleanRender()).doors) {
    EXPECT_EQ(d.state, DoorState::kClosed);
  }
}

TEST(RealismTest, CameraMisalignmentIsDrawnWithinItsBoundsAndOffLeavesTheCamera) {
  const RealismOptions on = Only(&RealismOptions::camera_misalignment);
  std::mt19937_64 rng(kSeed);
  bool pitched = false;
  for (int k = 0; k < 50; ++k) {
    const CameraModel c = DrawCamera(on, CameraModel{}, rng);
    EXPECT_LE(std::abs(c.roll_deg), on.max_roll_deg);
    EXPECT_LE(std::abs(c.pitch_deg), on.max_pitch_deg);
    EXPECT_GE(c.k1, on.min_k1);
    EXPECT_LE(c.k1, on.max_k1);
    pitched |= std::abs(c.pitch_deg) > 1.0;
  }
  EXPECT_TRUE(pitched);
  const CameraModel same = DrawCamera(CleanRender(), CameraModel{}, rng);
  EXPECT_EQ(same.roll_deg, CameraModel{}.roll_deg);
  EXPECT_EQ(same.pitch_deg, 0.0);
  EXPECT_EQ(same.k1, CameraModel{}.k1);
}

TEST(RealismTest, PitchedCameraKeepsJambTruthOnTheRenderedEdge) {
  CameraModel camera;
  camera.pitch_deg = 3.0;
  camera.roll_deg = 1.0;
  camera.k1 = -0.05;
  const CameraRenderer renderer(camera);
  const Scene scene(TwoDoors());
  std::mt19937_64 rng(5);
  const RenderedFrame f = renderer.Render(scene, {138.0, 0.0, 0.0}, NoNoise(), rng);
  ASSERT_FALSE(f.truth.doors.empty());
  const DoorTruth& d = f.truth.doors.front();
  ASSERT_TRUE(d.both_jambs_visible);
  // The left jamb: wall/casing (dark casing) then leaf; on the centre row the step from the
  // casing (70) to the leaf (125) crosses its middle within a pixel of the truth.
  const int v = 240;  // nearest row to the centre row 239.5
  const int c = static_cast<int>(std::lround(d.left_column_px));
  double best = 1e9;
  for (int u = c - 3; u < c + 3; ++u) {
    const double a = f.image.at<std::uint8_t>(v, u), b = f.image.at<std::uint8_t>(v, u + 1);
    if (b - a > 20) best = std::min(best, std::abs(u + 0.5 - d.left_column_px));
  }
  EXPECT_LT(best, 1.5);
}

TEST(RealismTest, IlluminationDrawsGradientsAndVignettingOnlyWhenOn) {
  std::mt19937_64 rng(kSeed);
  Illumination base;
  base.noise_stddev = 2.0;
  const Illumination same = DrawIllumination(CleanRender(), base, rng);
  EXPECT_EQ(same.gain, 1.0);
  EXPECT_EQ(same.vignetting, 0.0);
  const RealismOptions on = Only(&RealismOptions::illumination);
  const Illumination drawn = DrawIllumination(on, base, rng);
  EXPECT_GE(drawn.gain, on.min_gain);
  EXPECT_LE(drawn.gain, on.max_gain);
  EXPECT_LE(std::abs(drawn.vertical_gradient), on.max_vertical_gradient);
  EXPECT_GE(drawn.noise_stddev, on.min_noise);
  // Vignetting darkens the corners of a uniform wall.
  Illumination vignette = NoNoise();
  vignette.vignetting = 0.3;
  CameraModel camera;
  camera.k1 = 0.0;
  const CameraRenderer renderer(camera);
  HallwayOptions options;
  options.width_in = 80.0;  // the wall fills the frame
  const Scene wall(MakeStraightHallway({HallwayFeature::Wall(600)}, options));
  std::mt19937_64 r(1);
  const cv::Mat img = renderer.Render(wall, {300.0, 0.0, 0.0}, vignette, r).image;
  EXPECT_LT(img.at<std::uint8_t>(150, 5) + 15, img.at<std::uint8_t>(150, 255));
}

TEST(RealismTest, TheSameSeedGivesTheSameHallwayAndAnotherSeedAnother) {
  const RealismOptions all = FullRealism();
  const World a = Applied(ManyDoors(30), all, 11);
  const World b = Applied(ManyDoors(30), all, 11);
  const World c = Applied(ManyDoors(30), all, 12);
  ASSERT_EQ(a.decorations.size(), b.decorations.size());
  for (std::size_t k = 0; k < a.decorations.size(); ++k) {
    EXPECT_EQ(a.decorations[k].offset_in, b.decorations[k].offset_in);
  }
  bool differs = a.decorations.size() != c.decorations.size();
  for (std::size_t k = 0; k < a.doors.size(); ++k) {
    EXPECT_EQ(a.doors[k].face_intensity, b.doors[k].face_intensity);
    differs |= a.doors[k].face_intensity != c.doors[k].face_intensity;
  }
  EXPECT_TRUE(differs);
}

TEST(RealismTest, BadOptionsAreRejected) {
  RealismOptions o = FullRealism();
  o.dark_door_share = 0.9;
  o.white_door_share = 0.2;
  EXPECT_THROW(ValidateRealism(o), std::invalid_argument);
  o = FullRealism();
  o.max_roll_deg = 20.0;
  EXPECT_THROW(ValidateRealism(o), std::invalid_argument);
  EXPECT_NO_THROW(ValidateRealism(FullRealism()));
}

}  // namespace
}  // namespace stickrep::world
