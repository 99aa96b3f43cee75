#pragma once

#include <Eigen/Core>
#include <limits>
#include <optional>
#include <vector>

#include "world/world.h"

namespace stickrep::world {

// What a panel of the scene is, so ground truth and the sensors can tell them apart.
enum class PanelKind { kWall, kHeader, kFrame, kLeaf, kDecoration, kBaseboard, kSeam };

// One flat vertical rectangle of the compiled scene: the segment p0 -> p1 in the building
// plane, standing from bottom_in to top_in. Walls are split around door openings; frames,
// leaves, baseboards and decorations become panels of their own.
struct Panel {
  Eigen::Vector2d p0_in;
  Eigen::Vector2d p1_in;
  double bottom_in = 0.0;
  double top_in = 96.0;
  int intensity = 128;
  SurfaceType surface = SurfaceType::kConcrete;
  PanelKind kind = PanelKind::kWall;
  int door_index = -1;  // the door a frame, leaf or header belongs to
  // False for flush marks (posters, baseboards, seams): they sit on a wall face and give
  // the sonar no echo of their own.
  bool acoustic = true;
};

// Result of a ray cast.
struct RayHit {
  double distance_in = 0.0;  // along the unit ray direction
  Eigen::Vector2d point_in;
  SurfaceType surface = SurfaceType::kConcrete;
  double incidence_rad = 0.0;  // between the ray and the panel normal, 0..pi/2
  int panel_index = -1;
};

// Nearest point of the scene inside a sensing wedge (the sonar cone model, §5.4).
struct ConeHit {
  double distance_in = 0.0;  // from the apex to the nearest point inside the wedge
  Eigen::Vector2d point_in;
  SurfaceType surface = SurfaceType::kConcrete;
  double incidence_rad = 0.0;  // between the wedge axis and the panel normal, 0..pi/2
  int panel_index = -1;
};

inline constexpr double kAnyHeight = std::numeric_limits<double>::quiet_NaN();

// The world compiled into panels, ready for ray casting and rendering. Built once per
// world (doors open or close by rebuilding); all queries are const and thread-safe.
class Scene {
 public:
  // Throws std::invalid_argument when a door or decoration names a missing wall, does not
  // fit on its wall, or a wall has zero length.
  explicit Scene(World world);

  const World& world() const { return world_; }
  const std::vector<Panel>& panels() const { return panels_; }

  // First acoustic panel hit by the ray from origin along direction (need not be unit),
  // within max_range_in. With height_in given, only panels spanning that height count
  // (a sonar at 30 in passes under nothing but sees no door header either).
  std::optional<RayHit> Raycast(const Eigen::Vector2d& origin_in, const Eigen::Vector2d& direction,
                                double max_range_in, double height_in = kAnyHeight) const;

  // Nearest point of any acoustic panel inside the wedge with the given apex, axis and
  // half angle (< 90°), within max_range_in. The nearest point is never occluded, so this
  // is exact without a visibility test.
  std::optional<ConeHit> NearestInCone(const Eigen::Vector2d& apex_in, const Eigen::Vector2d& axis,
                                       double half_angle_rad, double max_range_in,
                                       double height_in = kAnyHeight) const;

  // All panels crossed by the ray (any kind, any height), nearest first, with
  // 0 < t <= max_t, where `t` is in units of the (non-normalised) direction. Only the
  // panels listed in `subset` are tested when it is given (the renderer culls once per
  // frame). Used by the renderer.
  struct Crossing {
    double t;
    int panel_index;
    double cos_incidence;
  };
  void CastAll(const Eigen::Vector2d& origin_in, const Eigen::Vector2d& direction, double max_t,
               std::vector<Crossing>* out, const std::vector<int>* subset = nullptr) const;

  // Indices of the panels with some point within max_range_in of `center_in` and in front
  // of the plane through center_in with normal `forward`.
  std::vector<int> PanelsNear(const Eigen::Vector2d& center_in, const Eigen::Vector2d& forward,
                              double max_range_in) const;

  // The two jamb edges of a door in the building plane: the inner edges of the frame
  // casing, on its face (just in front of the wall face), {end nearer wall.a_in, other}.
  std::pair<Eigen::Vector2d, Eigen::Vector2d> JambPoints(int door_index) const;

  // Unit normal of a panel (right of p0 -> p1).
  static Eigen::Vector2d Normal(const Panel& panel);

 private:
  void Compile();

  World world_;
  std::vector<Panel> panels_;
};

}  // namespace stickrep::world
