#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace stickrep::world {

// Pose of a body in the building plane: position in inches, heading in radians measured
// counter-clockwise from the world +x axis. Monogram: X_WR is the pose of robot R in W.
struct Pose2d {
  double x_in = 0.0;
  double y_in = 0.0;
  double theta_rad = 0.0;

  Eigen::Vector2d position() const { return {x_in, y_in}; }
};

// Acoustic surface class of a wall face; the three surfaces of the ultrasonic study
// (§4.3, Tables 4.2 and 4.3).
enum class SurfaceType { kConcrete, kWood, kCloth };

const char* ToString(SurfaceType surface);

// A wall of the hallway: a vertical plane standing on the building plane from `a_in` to
// `b_in`. The hallway (the face the robot sees) is on the RIGHT of the direction a -> b,
// i.e. the face normal is (dy, -dx) of the unit direction; doors open "inward" away from
// that face and "outward" toward it.
struct WallSegment {
  Eigen::Vector2d a_in{0.0, 0.0};
  Eigen::Vector2d b_in{0.0, 0.0};
  double height_in = 96.0;  // floor to ceiling; not in the text, a common 8 ft hallway
  SurfaceType surface = SurfaceType::kConcrete;
  int intensity = 170;  // grey level 0..255 of the face under unit illumination
};

enum class DoorState { kClosed, kOpenInward, kOpenOutward };

const char* ToString(DoorState state);

// Supplemental marks carried by a door edge (Table 6.8 lists window and poster patterns).
enum class DoorPattern { kNone, kWindow, kPoster };

// A door set into a wall. The opening spans [offset_in, offset_in + width_in] measured
// from the wall's `a_in` end; the opening width is the door class (§4.1.2: 30, 32, 36,
// 40 in single doors; 60 = 30/30 and 72 = 36/36 double doors) and is what the vertical
// edge ribbon detector measures between the two jambs. The frame (casing) lies on the
// wall face outside the opening, `frame_width_in` wide on each side and over the top.
struct DoorFeature {
  int wall_index = 0;
  double offset_in = 0.0;
  double width_in = 36.0;
  double height_in = 80.0;      // standard 6'8" door
  double frame_width_in = 3.0;  // casing width; not in the text
  int frame_intensity = 70;     // dark painted steel frame against a light wall (C2, §5.1)
  int face_intensity = 125;     // wood or painted leaf
  bool double_door = false;     // two leaves of width/2 meeting in the middle
  DoorState state = DoorState::kClosed;
  double open_angle_rad = 0.0;  // leaf rotation about the hinge, 0 = closed position
  bool hinge_at_start = true;   // hinge on the jamb nearest wall.a_in (single doors)
  DoorPattern pattern = DoorPattern::kNone;
  SurfaceType leaf_surface = SurfaceType::kWood;
};

// A flat mark on a wall face: a poster, a notice, a scuff or a light switch plate. These
// are the "accidental marks" the detector's threshold and clumping must tolerate (§4.1.1).
struct WallDecoration {
  int wall_index = 0;
  double offset_in = 0.0;  // left edge, from the wall's a_in end
  double width_in = 24.0;
  double bottom_in = 42.0;
  double top_in = 78.0;
  int intensity = 230;
  // Stacking order of marks that overlap (a glazed board's pane sits on its frame): a mark
  // of a higher layer is drawn in front of a lower one.
  int layer = 0;
};

// A ceiling luminaire: a bright rectangle on the ceiling, centred at center_in, `length_in`
// along `along` (unit) and `width_in` across it. Seen directly, and mirrored in a glossy
// floor, it is the bright clutter at the top and bottom of hallway frames.
struct CeilingLight {
  Eigen::Vector2d center_in{0.0, 0.0};
  Eigen::Vector2d along{1.0, 0.0};
  double length_in = 48.0;
  double width_in = 12.0;
  int intensity = 250;
};

// The simulated building: walls with doors and decorations, plus the floor and ceiling
// shading the camera renderer needs. Plain data, independent of the map file format; a
// converter from StickRep rings fills it.
struct World {
  std::vector<WallSegment> walls;
  std::vector<DoorFeature> doors;
  std::vector<WallDecoration> decorations;
  std::vector<CeilingLight> ceiling_lights;
  double ceiling_height_in = 96.0;
  int floor_intensity = 95;
  int ceiling_intensity = 205;
  double baseboard_height_in = 4.0;  // dark strip at the foot of walls; 0 for none
  int baseboard_intensity = 50;
  // Share of the light reaching a glossy floor that it mirrors (0: matte). A waxed hallway
  // floor shows the doors and the ceiling lights upside down below the baseboard.
  double floor_reflectance = 0.0;
};

// Legal door classes in inches (§4.1.2, §6.1): 30, 32, 36, 40, 60 (30/30), 72 (36/36).
inline constexpr int kDoorClassesIn[] = {30, 32, 36, 40, 60, 72};

// The class whose width is within 0.5 in of `width_in`, or nullopt.
std::optional<int> DoorClassForWidth(double width_in);

// One element laid along the feature side of a straight hallway.
struct HallwayFeature {
  enum class Kind { kWall, kDoor, kPoster };
  Kind kind = Kind::kWall;
  double length_in = 0.0;  // wall length, door width (the class), or wall carrying a poster
  DoorState state = DoorState::kClosed;
  double open_angle_rad = 0.0;
  DoorPattern pattern = DoorPattern::kNone;

  static HallwayFeature Wall(double length_in);
  static HallwayFeature Door(double width_in, DoorState state = DoorState::kClosed,
                             double open_angle_rad = 0.0);
  static HallwayFeature Poster(double length_in);
};

// Shape of the straight hallway built by MakeStraightHallway.
struct HallwayOptions {
  double width_in = 72.0;  // wall to wall; not in the text, a 6 ft corridor
  double wall_height_in = 96.0;
  double room_depth_in = 144.0;  // back wall of the rooms seen through open doors
  SurfaceType feature_surface = SurfaceType::kConcrete;
  SurfaceType opposite_surface = SurfaceType::kConcrete;
  int feature_wall_intensity = 175;
  int opposite_wall_intensity = 160;
  int room_wall_intensity = 110;
  DoorFeature door_template;  // frame, leaf and height used for every door
};

// A straight hallway along +x starting at x = 0. The features are laid in order along the
// wall at y = +width/2 (the robot's left when it travels toward +x); the opposite wall at
// y = -width/2 is plain. Rooms of depth room_depth_in lie behind the feature wall, so an
// open door shows a back wall. Doors of 60 and 72 in are laid as double doors. Throws
// std::invalid_argument on a non-positive length.
World MakeStraightHallway(const std::vector<HallwayFeature>& features,
                          const HallwayOptions& options = {});

// Total length of the features laid by MakeStraightHallway.
double HallwayLength(const std::vector<HallwayFeature>& features);

}  // namespace stickrep::world
