#include "world/world.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace stickrep::world {

const char* ToString(SurfaceType surface) {
  switch (surface) {
    case SurfaceType::kConcrete:
      return "concrete";
    case SurfaceType::kWood:
      return "wood";
    case SurfaceType::kCloth:
      return "cloth";
  }
  return "unknown";
}

const char* ToString(DoorState state) {
  switch (state) {
    case DoorState::kClosed:
      return "closed";
    case DoorState::kOpenInward:
      return "open_inward";
    case DoorState::kOpenOutward:
      return "open_outward";
  }
  return "unknown";
}

std::optional<int> DoorClassForWidth(double width_in) {
  for (int c : kDoorClassesIn) {
    if (std::abs(width_in - c) <= 0.5) return c;
  }
  return std::nullopt;
}

HallwayFeature HallwayFeature::Wall(double length_in) {
  HallwayFeature f;
  f.kind = Kind::kWall;
  f.length_in = length_in;
  return f;
}

HallwayFeature HallwayFeature::Door(double width_in, DoorState state, double open_angle_rad) {
  HallwayFeature f;
  f.kind = Kind::kDoor;
  f.length_in = width_in;
  f.state = state;
  f.open_angle_rad = open_angle_rad;
  return f;
}

HallwayFeature HallwayFeature::Poster(double length_in) {
  HallwayFeature f;
  f.kind = Kind::kPoster;
  f.length_in = length_in;
  return f;
}

double HallwayLength(const std::vector<HallwayFeature>& features) {
  double total = 0.0;
  for (const HallwayFeature& f : features) total += f.length_in;
  return total;
}

World MakeStraightHallway(const std::vector<HallwayFeature>& features,
                          const HallwayOptions& options) {
  if (options.width_in <= 0.0 || options.wall_height_in <= 0.0 || options.room_depth_in <= 0.0) {
    throw std::invalid_argument("hallway width, wall height and room depth must be > 0 in");
  }
  for (size_t i = 0; i < features.size(); ++i) {
    if (!(features[i].length_in > 0.0)) {
      throw std::invalid_argument("hallway feature " + std::to_string(i) +
                                  ": length_in must be > 0 (got " +
                                  std::to_string(features[i].length_in) + ")");
    }
  }
  const double length_in = HallwayLength(features);
  const double half = options.width_in / 2.0;

  World world;
  world.ceiling_height_in = options.wall_height_in;

  // Wall 0: the feature wall, running +x so that the hallway lies on its right (-y side).
  WallSegment feature_wall;
  feature_wall.a_in = {0.0, half};
  feature_wall.b_in = {length_in, half};
  feature_wall.height_in = options.wall_height_in;
  feature_wall.surface = options.feature_surface;
  feature_wall.intensity = options.feature_wall_intensity;
  world.walls.push_back(feature_wall);

  // Wall 1: the plain opposite wall, running -x so that the hallway is again on its right.
  WallSegment opposite;
  opposite.a_in = {length_in, -half};
  opposite.b_in = {0.0, -half};
  opposite.height_in = options.wall_height_in;
  opposite.surface = options.opposite_surface;
  opposite.intensity = options.opposite_wall_intensity;
  world.walls.push_back(opposite);

  // Wall 2: the back wall of the rooms behind the feature wall, facing the hallway.
  WallSegment back;
  back.a_in = {0.0, half + options.room_depth_in};
  back.b_in = {length_in, half + options.room_depth_in};
  back.height_in = options.wall_height_in;
  back.intensity = options.room_wall_intensity;
  world.walls.push_back(back);

  double x = 0.0;
  for (const HallwayFeature& f : features) {
    switch (f.kind) {
      case HallwayFeature::Kind::kWall:
        break;
      case HallwayFeature::Kind::kDoor: {
        DoorFeature door = options.door_template;
        door.wall_index = 0;
        door.offset_in = x;
        door.width_in = f.length_in;
        door.state = f.state;
        door.open_angle_rad = f.open_angle_rad;
        door.pattern = f.pattern;
        door.double_door = f.length_in > 50.0;  // 30/30 and 36/36 (§4.1.2)
        world.doors.push_back(door);
        break;
      }
      case HallwayFeature::Kind::kPoster: {
        WallDecoration poster;
        poster.wall_index = 0;
        poster.width_in = std::min(24.0, 0.6 * f.length_in);
        poster.offset_in = x + (f.length_in - poster.width_in) / 2.0;
        world.decorations.push_back(poster);
        break;
      }
    }
    x += f.length_in;
  }
  return world;
}

}  // namespace stickrep::world
