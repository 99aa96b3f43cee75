#include "world/realism.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/units.h"

namespace stickrep::world {
namespace {

constexpr double kMinWallForClutterIn = 12.0;
// Light marks are this much brighter than the wall (pilasters, panels); ours.
constexpr int kPilasterLift = 45;

double Uniform(std::mt19937_64& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

int ClampGrey(double v) { return static_cast<int>(std::clamp(std::lround(v), 0L, 255L)); }

void Require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("realism: " + what);
}

// The doors of wall wi, in order along it.
std::vector<int> DoorsOnWall(const World& world, int wi) {
  std::vector<int> doors;
  for (int k = 0; k < static_cast<int>(world.doors.size()); ++k) {
    if (world.doors[k].wall_index == wi) doors.push_back(k);
  }
  std::sort(doors.begin(), doors.end(), [&](int a, int b) {
    return world.doors[a].offset_in < world.doors[b].offset_in;
  });
  return doors;
}

// Stretches [s0, s1] of wall wi free of doors and their casings.
std::vector<std::pair<double, double>> FreeStretches(const World& world, int wi) {
  const WallSegment& wall = world.walls[wi];
  const double len = (wall.b_in - wall.a_in).norm();
  std::vector<std::pair<double, double>> free;
  double s = 0.0;
  for (int k : DoorsOnWall(world, wi)) {
    const DoorFeature& d = world.doors[k];
    free.push_back({s, d.offset_in - d.frame_width_in});
    s = d.offset_in + d.width_in + d.frame_width_in;
  }
  free.push_back({s, len});
  std::vector<std::pair<double, double>> out;
  for (const auto& f : free) {
    if (f.second - f.first >= kMinWallForClutterIn) out.push_back(f);
  }
  return out;
}

void AddCeilingLights(const RealismOptions& o, World* world) {
  for (const WallSegment& wall : world->walls) {
    const Eigen::Vector2d d = wall.b_in - wall.a_in;
    const double len = d.norm();
    if (len < o.light_length_in) continue;
    const Eigen::Vector2d u = d / len;
    const Eigen::Vector2d n{u.y(), -u.x()};  // toward the hallway
    for (double s = 0.5 * o.light_spacing_in; s + 0.5 * o.light_length_in <= len;
         s += o.light_spacing_in) {
      CeilingLight light;
      light.center_in = wall.a_in + u * s + n * o.light_offset_in;
      light.along = u;
      light.length_in = o.light_length_in;
      light.width_in = o.light_width_in;
      world->ceiling_lights.push_back(light);
    }
  }
}

// A board on wall wi from s0: a dark-framed glazed pane, or a plain high-contrast poster.
void AddBoard(const RealismOptions& o, int wi, double s0, double width, std::mt19937_64& rng,
              World* world) {
  const int wall_grey = world->walls[wi].intensity;
  const bool glazed = Uniform(rng, 0.0, 1.0) < o.glazed_share;
  const double bottom = Uniform(rng, 34.0, 48.0);
  const double height = Uniform(rng, 18.0, 36.0);
  WallDecoration board;
  board.wall_index = wi;
  board.offset_in = s0;
  board.width_in = width;
  board.bottom_in = bottom;
  board.top_in = bottom + height;
  if (glazed) {
    board.intensity = ClampGrey(Uniform(rng, 35.0, 80.0));  // aluminium or wood frame
    world->decorations.push_back(board);
    WallDecoration pane = board;
    const double rim = 1.5;
    pane.offset_in += rim;
    pane.width_in -= 2.0 * rim;
    pane.bottom_in += rim;
    pane.top_in -= rim;
    pane.intensity = ClampGrey(Uniform(rng, 205.0, 250.0));  // glass catching the lights
    pane.layer = 1;
    world->decorations.push_back(pane);
  } else {
    // A poster or cork board: darker or brighter than the wall, never like it.
    const bool dark = Uniform(rng, 0.0, 1.0) < 0.6;
    board.intensity = dark ? ClampGrey(Uniform(rng, 40.0, wall_grey - 60.0))
                           : ClampGrey(Uniform(rng, std::min(250.0, wall_grey + 35.0), 255.0));
    world->decorations.push_back(board);
  }
}

void AddNoticeBoards(const RealismOptions& o, std::mt19937_64& rng, World* world) {
  for (int wi = 0; wi < static_cast<int>(world->walls.size()); ++wi) {
    for (const auto& [s0, s1] : FreeStretches(*world, wi)) {
      const double room = s1 - s0 - 8.0;  // 4 in clear of a casing or corner
      if (room < o.min_board_width_in) continue;
      const double expected = (s1 - s0) / o.notice_board_spacing_in;
      if (Uniform(rng, 0.0, 1.0) >= std::min(1.0, expected)) continue;
      const double width =
          Uniform(rng, o.min_board_width_in, std::min(o.max_board_width_in, room));
      const double at = s0 + 4.0 + Uniform(rng, 0.0, room - width);
      AddBoard(o, wi, at, width, rng, world);
    }
  }
}

// A dark wood leaf in a frame that is, with equal odds, dark metal or wood like the leaf
// (then the opening barely shows and the casing's outer edges are the door's) or painted
// trim a shade under the wall.
void MakeDark(DoorFeature* door, int wall_intensity, std::mt19937_64& rng) {
  door->face_intensity = ClampGrey(Uniform(rng, 40.0, 80.0));
  const double u = Uniform(rng, 0.0, 1.0);
  door->frame_intensity = u < 0.5 ? ClampGrey(door->face_intensity + Uniform(rng, -15.0, 10.0))
                                  : ClampGrey(wall_intensity - Uniform(rng, 10.0, 30.0));
}

// Pilasters and panels between doors closer than pilaster_max_gap_in.
void AddPilasters(const RealismOptions& o, std::mt19937_64& rng, World* world) {
  for (int wi = 0; wi < static_cast<int>(world->walls.size()); ++wi) {
    const std::vector<int> doors = DoorsOnWall(*world, wi);
    const WallSegment& wall = world->walls[wi];
    for (std::size_t i = 0; i + 1 < doors.size(); ++i) {
      DoorFeature& a = world->doors[doors[i]];
      DoorFeature& b = world->doors[doors[i + 1]];
      const double s0 = a.offset_in + a.width_in + a.frame_width_in;
      const double s1 = b.offset_in - b.frame_width_in;
      if (s1 - s0 < 4.0 || s1 - s0 > o.pilaster_max_gap_in) continue;
      MakeDark(&a, wall.intensity, rng);
      MakeDark(&b, wall.intensity, rng);
      WallDecoration strip;
      strip.wall_index = wi;
      const bool panel = Uniform(rng, 0.0, 1.0) < 0.5;
      const double width = panel ? s1 - s0 : std::min(s1 - s0, Uniform(rng, 8.0, 16.0));
      strip.offset_in = 0.5 * (s0 + s1) - 0.5 * width;
      strip.width_in = width;
      strip.bottom_in = world->baseboard_height_in;
      strip.top_in = wall.height_in;
      strip.intensity = ClampGrey(wall.intensity + kPilasterLift * Uniform(rng, 0.5, 1.0));
      world->decorations.push_back(strip);
    }
  }
}

void DrawDoorLooks(const RealismOptions& o, std::mt19937_64& rng, World* world) {
  for (DoorFeature& door : world->doors) {
    const double u = Uniform(rng, 0.0, 1.0);
    if (u < o.dark_door_share) {
      MakeDark(&door, world->walls[door.wall_index].intensity, rng);
    } else if (u < o.dark_door_share + o.white_door_share) {
      // White on white: the leaf within a few grey levels of its wall, the casing a shade
      // darker (paint edge and shadow).
      const int wall = world->walls[door.wall_index].intensity;
      door.face_intensity = ClampGrey(wall + Uniform(rng, -8.0, 6.0));
      door.frame_intensity = ClampGrey(wall - Uniform(rng, 15.0, 30.0));
    }
  }
}

void OpenAjar(const RealismOptions& o, std::mt19937_64& rng, World* world) {
  for (DoorFeature& door : world->doors) {
    const double u = Uniform(rng, 0.0, 1.0);
    const double angle = Uniform(rng, 2.0, o.max_ajar_deg);
    if (door.state != DoorState::kClosed || u >= o.ajar_share) continue;
    door.state = DoorState::kOpenInward;
    door.open_angle_rad = angle * kPi / 180.0;
  }
}

}  // namespace

RealismOptions FullRealism() {
  RealismOptions o;
  o.baseboards = o.floor_reflections = o.ceiling_lights = o.notice_boards = o.pilasters =
      o.door_appearance = o.doors_ajar = o.camera_misalignment = o.illumination = true;
  return o;
}

RealismOptions CleanRender() {
  RealismOptions o;
  o.floor_reflections = o.ceiling_lights = o.notice_boards = o.pilasters = o.door_appearance =
      o.doors_ajar = o.camera_misalignment = o.illumination = false;
  return o;
}

void ValidateRealism(const RealismOptions& o) {
  Require(o.baseboard_height_in >= 0.0 && o.baseboard_height_in <= 12.0,
          "baseboard_height_in must be in [0, 12] in");
  Require(o.floor_reflectance >= 0.0 && o.floor_reflectance <= 0.8,
          "floor_reflectance must be in [0, 0.8]");
  Require(o.light_spacing_in >= o.light_length_in && o.light_length_in > 0.0 &&
              o.light_width_in > 0.0 && o.light_offset_in >= 0.0,
          "ceiling lights need 0 < length <= spacing, width > 0, offset >= 0 in");
  Require(o.notice_board_spacing_in > 0.0 && o.min_board_width_in > 0.0 &&
              o.max_board_width_in >= o.min_board_width_in && o.glazed_share >= 0.0 &&
              o.glazed_share <= 1.0,
          "notice boards need spacing > 0, 0 < min <= max width, glazed_share in [0, 1]");
  Require(o.pilaster_max_gap_in >= 0.0, "pilaster_max_gap_in must be >= 0 in");
  Require(o.dark_door_share >= 0.0 && o.white_door_share >= 0.0 &&
              o.dark_door_share + o.white_door_share <= 1.0,
          "door shares must be >= 0 and add up to at most 1");
  Require(o.ajar_share >= 0.0 && o.ajar_share <= 1.0 && o.max_ajar_deg >= 2.0 &&
              o.max_ajar_deg <= 45.0,
          "ajar_share in [0, 1], max_ajar_deg in [2, 45] deg");
  Require(o.max_roll_deg >= 0.0 && o.max_roll_deg <= 10.0 && o.max_pitch_deg >= 0.0 &&
              o.max_pitch_deg <= 10.0 && o.min_k1 >= -0.3 && o.max_k1 <= 0.5 &&
              o.min_k1 <= o.max_k1,
          "camera: roll and pitch in [0, 10] deg, -0.3 <= min_k1 <= max_k1 <= 0.5");
  Require(o.min_gain > 0.0 && o.max_gain >= o.min_gain && o.max_offset >= 0.0 &&
              o.max_gradient >= 0.0 && o.max_gradient < 1.0 && o.max_vertical_gradient >= 0.0 &&
              o.max_vertical_gradient < 1.0 && o.max_vignetting >= 0.0 &&
              o.max_vignetting < 1.0 && o.min_noise >= 0.0 && o.max_noise >= o.min_noise,
          "illumination: 0 < min_gain <= max_gain, gradients and vignetting in [0, 1), "
          "0 <= min_noise <= max_noise");
}

void ApplyRealism(const RealismOptions& o, std::mt19937_64& rng, World* world) {
  ValidateRealism(o);
  // Each feature draws from its own generator, forked in a fixed order, so switching one
  // feature never changes what another draws.
  std::mt19937_64 boards_rng(rng()), pilaster_rng(rng()), looks_rng(rng()), ajar_rng(rng());
  if (o.baseboards) {
    world->baseboard_height_in = o.baseboard_height_in;
    world->baseboard_intensity = o.baseboard_intensity;
  } else {
    world->baseboard_height_in = 0.0;
  }
  world->floor_reflectance = o.floor_reflections ? o.floor_reflectance : 0.0;
  if (o.ceiling_lights) AddCeilingLights(o, world);
  if (o.door_appearance) DrawDoorLooks(o, looks_rng, world);
  if (o.pilasters) AddPilasters(o, pilaster_rng, world);
  if (o.notice_boards) AddNoticeBoards(o, boards_rng, world);
  if (o.doors_ajar) OpenAjar(o, ajar_rng, world);
}

CameraModel DrawCamera(const RealismOptions& o, CameraModel camera, std::mt19937_64& rng) {
  if (!o.camera_misalignment) return camera;
  camera.roll_deg = Uniform(rng, -o.max_roll_deg, o.max_roll_deg);
  camera.pitch_deg = Uniform(rng, -o.max_pitch_deg, o.max_pitch_deg);
  camera.k1 = Uniform(rng, o.min_k1, o.max_k1);
  return camera;
}

Illumination DrawIllumination(const RealismOptions& o, const Illumination& base,
                              std::mt19937_64& rng) {
  if (!o.illumination) return base;
  Illumination light = base;
  light.gain = Uniform(rng, o.min_gain, o.max_gain);
  light.offset = Uniform(rng, -o.max_offset, o.max_offset);
  light.gradient = Uniform(rng, -o.max_gradient, o.max_gradient);
  light.vertical_gradient = Uniform(rng, -o.max_vertical_gradient, o.max_vertical_gradient);
  light.vignetting = Uniform(rng, 0.0, o.max_vignetting);
  light.noise_stddev = Uniform(rng, o.min_noise, o.max_noise);
  return light;
}

}  // namespace stickrep::world
