#include "world/scene.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "common/units.h"

namespace stickrep::world {
namespace {

// Offsets of flush parts in front of their wall face. Large enough to order the panels
// along a ray without depth fighting, small enough to be invisible at hallway ranges.
constexpr double kDecorationOffsetIn = 0.05;
constexpr double kFrameOffsetIn = 0.10;
// A closed leaf sits in its frame's stop, behind the wall face.
constexpr double kLeafRecessIn = 1.0;
// The dark gap where the two leaves of a double door meet.
constexpr double kSeamWidthIn = 0.4;
constexpr int kSeamIntensity = 40;
constexpr double kMinT = 1e-9;

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

Eigen::Vector2d Rotate(const Eigen::Vector2d& v, double angle_rad) {
  const double c = std::cos(angle_rad);
  const double s = std::sin(angle_rad);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

bool SpansHeight(const Panel& p, double height_in) {
  return std::isnan(height_in) || (p.bottom_in <= height_in && height_in <= p.top_in);
}

// Intersection parameter t of origin + t * dir with the panel segment, or a negative value.
double Intersect(const Panel& p, const Eigen::Vector2d& origin, const Eigen::Vector2d& dir) {
  const Eigen::Vector2d e = p.p1_in - p.p0_in;
  const double denom = Cross(dir, e);
  if (std::abs(denom) < 1e-12) return -1.0;  // parallel: a grazing ray sees no face
  const Eigen::Vector2d w = p.p0_in - origin;
  const double t = Cross(w, e) / denom;
  const double s = Cross(w, dir) / denom;
  if (s < 0.0 || s > 1.0) return -1.0;
  return t;
}

// Throws std::invalid_argument for a wall of zero length, a door or decoration that names a
// missing wall, or a door that does not fit on its wall (Scene's constructor contract).
void CheckWorld(const World& world) {
  const int n_walls = static_cast<int>(world.walls.size());
  for (int i = 0; i < n_walls; ++i) {
    const WallSegment& w = world.walls[i];
    if ((w.b_in - w.a_in).norm() < 1e-6) {
      throw std::invalid_argument("wall " + std::to_string(i) + " has zero length");
    }
  }
  for (size_t k = 0; k < world.doors.size(); ++k) {
    const DoorFeature& door = world.doors[k];
    if (door.wall_index < 0 || door.wall_index >= n_walls) {
      throw std::invalid_argument("door " + std::to_string(k) + " names missing wall " +
                                  std::to_string(door.wall_index));
    }
    const WallSegment& w = world.walls[door.wall_index];
    const double len = (w.b_in - w.a_in).norm();
    if (!(door.width_in > 0.0) || door.offset_in < 0.0 ||
        door.offset_in + door.width_in > len + 1e-6) {
      throw std::invalid_argument(
          "door " + std::to_string(k) + " (offset " + std::to_string(door.offset_in) +
          " in, width " + std::to_string(door.width_in) + " in) does not fit on wall " +
          std::to_string(door.wall_index) + " of length " + std::to_string(len) + " in");
    }
  }
  for (size_t k = 0; k < world.decorations.size(); ++k) {
    const WallDecoration& dec = world.decorations[k];
    if (dec.wall_index < 0 || dec.wall_index >= n_walls) {
      throw std::invalid_argument("decoration " + std::to_string(k) + " names missing wall " +
                                  std::to_string(dec.wall_index));
    }
  }
}

// Adds the panels of one wall to the scene. A panel is placed by s, along the wall from its
// a_in end, and out, in front of the wall face (toward the hallway; negative: behind it).
class WallPanels {
 public:
  WallPanels(const WallSegment& wall, double len, std::vector<Panel>* panels)
      : a_in_(wall.a_in), d_((wall.b_in - wall.a_in) / len), n_(d_.y(), -d_.x()), panels_(panels) {}

  const Eigen::Vector2d& d() const { return d_; }  // unit, a_in -> b_in
  const Eigen::Vector2d& n() const { return n_; }  // toward the hallway

  Eigen::Vector2d At(double s, double out) const { return a_in_ + d_ * s + n_ * out; }

  // A panel from s0 to s1, bottom to top, at `out`; nothing when it is empty.
  void Add(double s0, double s1, double out, double bottom, double top, int intensity,
           SurfaceType surface, PanelKind kind, int door, bool acoustic) {
    if (s1 - s0 <= 1e-9 || top - bottom <= 1e-9) return;
    Panel p;
    p.p0_in = At(s0, out);
    p.p1_in = At(s1, out);
    p.bottom_in = bottom;
    p.top_in = top;
    p.intensity = intensity;
    p.surface = surface;
    p.kind = kind;
    p.door_index = door;
    p.acoustic = acoustic;
    panels_->push_back(p);
  }

  void Push(const Panel& p) { panels_->push_back(p); }

 private:
  Eigen::Vector2d a_in_;
  Eigen::Vector2d d_;
  Eigen::Vector2d n_;
  std::vector<Panel>* panels_;
};

// A wall face between openings, with its baseboard.
void AddWallPart(const World& world, const WallSegment& wall, double s0, double s1,
                 WallPanels* panels) {
  panels->Add(s0, s1, 0.0, 0.0, wall.height_in, wall.intensity, wall.surface, PanelKind::kWall, -1,
              true);
  if (world.baseboard_height_in > 0.0) {
    panels->Add(s0, s1, kDecorationOffsetIn, 0.0, world.baseboard_height_in,
                world.baseboard_intensity, wall.surface, PanelKind::kBaseboard, -1, false);
  }
}

// A door leaf as it hangs when closed.
struct Leaf {
  Eigen::Vector2d hinge;
  Eigen::Vector2d along;  // closed direction from the hinge to the free edge
  double width;
};

// Leaves: one, or two of half width hinged at both jambs.
std::vector<Leaf> DoorLeaves(const DoorFeature& door, const WallPanels& wall) {
  const double o0 = door.offset_in;
  const double o1 = door.offset_in + door.width_in;
  const Eigen::Vector2d& d = wall.d();
  std::vector<Leaf> leaves;
  const Eigen::Vector2d j0 = wall.At(o0, -kLeafRecessIn);
  const Eigen::Vector2d j1 = wall.At(o1, -kLeafRecessIn);
  if (door.double_door) {
    leaves.push_back({j0, d, door.width_in / 2.0});
    leaves.push_back({j1, -d, door.width_in / 2.0});
  } else if (door.hinge_at_start) {
    leaves.push_back({j0, d, door.width_in});
  } else {
    leaves.push_back({j1, -d, door.width_in});
  }
  return leaves;
}

// A mark on a leaf panel from u0 to u1 of its width: patterns ride on the leaf, just in
// front of its hallway face.
Panel LeafMark(const Panel& p, double u0, double u1, double bottom, double top, int intensity) {
  const Eigen::Vector2d ln = Scene::Normal(p);
  Panel m = p;
  const Eigen::Vector2d e = p.p1_in - p.p0_in;
  m.p0_in = p.p0_in + e * u0 + ln * kDecorationOffsetIn;
  m.p1_in = p.p0_in + e * u1 + ln * kDecorationOffsetIn;
  m.bottom_in = bottom;
  m.top_in = top;
  m.intensity = intensity;
  m.kind = PanelKind::kDecoration;
  m.acoustic = false;
  return m;
}

// The panel of one leaf of door k, swung open by `angle` (0: closed), and its pattern.
void AddLeaf(const Leaf& leaf, const DoorFeature& door, int k, double angle, WallPanels* wall) {
  // Rotating `along` toward -n swings the leaf into the room (inward), toward +n into
  // the hallway (outward). The sign of the turn depends on which jamb holds the hinge.
  const double side = Cross(leaf.along, wall->n()) > 0.0 ? 1.0 : -1.0;  // turn toward +n
  const double turn = door.state == DoorState::kOpenOutward ? side * angle : -side * angle;
  const Eigen::Vector2d dir = Rotate(leaf.along, turn);
  const Eigen::Vector2d tip = leaf.hinge + dir * leaf.width;
  // Orient the panel so its normal faces the hallway side of the closed leaf.
  Panel p;
  const bool forward = leaf.along.dot(wall->d()) > 0.0;
  p.p0_in = forward ? leaf.hinge : tip;
  p.p1_in = forward ? tip : leaf.hinge;
  p.bottom_in = 0.0;
  p.top_in = door.height_in;
  p.intensity = door.face_intensity;
  p.surface = door.leaf_surface;
  p.kind = PanelKind::kLeaf;
  p.door_index = k;
  wall->Push(p);
  if (door.pattern == DoorPattern::kWindow) {
    wall->Push(LeafMark(p, 0.55, 0.75, 40.0, 72.0, 215));  // narrow vision panel of pale glass
  } else if (door.pattern == DoorPattern::kPoster) {
    wall->Push(LeafMark(p, 0.25, 0.75, 46.0, 66.0, 235));
  }
}

// Door k on its wall: the header and frame around the opening, the leaves, and the seam
// between the leaves of a closed double door.
void AddDoor(const WallSegment& wall, const DoorFeature& door, int k, WallPanels* panels) {
  const double o0 = door.offset_in;
  const double o1 = door.offset_in + door.width_in;
  const double fw = door.frame_width_in;
  // The wall above the opening (a header) and the frame around it.
  panels->Add(o0, o1, 0.0, door.height_in, wall.height_in, wall.intensity, wall.surface,
              PanelKind::kHeader, k, true);
  panels->Add(o0 - fw, o0, kFrameOffsetIn, 0.0, door.height_in + fw, door.frame_intensity,
              SurfaceType::kWood, PanelKind::kFrame, k, false);
  panels->Add(o1, o1 + fw, kFrameOffsetIn, 0.0, door.height_in + fw, door.frame_intensity,
              SurfaceType::kWood, PanelKind::kFrame, k, false);
  panels->Add(o0, o1, kFrameOffsetIn, door.height_in, door.height_in + fw, door.frame_intensity,
              SurfaceType::kWood, PanelKind::kFrame, k, false);

  double angle = 0.0;
  if (door.state != DoorState::kClosed) {
    angle = std::clamp(door.open_angle_rad, 0.0, 0.5 * kPi + 0.35);
  }
  for (const Leaf& leaf : DoorLeaves(door, *panels)) AddLeaf(leaf, door, k, angle, panels);
  if (door.double_door && door.state == DoorState::kClosed) {
    const double mid = (o0 + o1) / 2.0;
    panels->Add(mid - kSeamWidthIn / 2.0, mid + kSeamWidthIn / 2.0,
                -kLeafRecessIn + kDecorationOffsetIn, 0.0, door.height_in, kSeamIntensity,
                door.leaf_surface, PanelKind::kSeam, k, false);
  }
}

// The panels of wall wi: its faces between openings, its doors, its decorations.
void CompileWall(const World& world, int wi, std::vector<Panel>* out) {
  const WallSegment& wall = world.walls[wi];
  const double len = (wall.b_in - wall.a_in).norm();
  WallPanels panels(wall, len, out);

  // Openings on this wall, in order along it.
  std::vector<int> doors;
  for (size_t k = 0; k < world.doors.size(); ++k) {
    if (world.doors[k].wall_index == wi) doors.push_back(static_cast<int>(k));
  }
  std::sort(doors.begin(), doors.end(),
            [&](int a, int b) { return world.doors[a].offset_in < world.doors[b].offset_in; });

  // Wall faces between openings, with their baseboards.
  double s = 0.0;
  for (int k : doors) {
    const DoorFeature& door = world.doors[k];
    AddWallPart(world, wall, s, door.offset_in, &panels);
    s = door.offset_in + door.width_in;
  }
  AddWallPart(world, wall, s, len, &panels);

  for (int k : doors) AddDoor(wall, world.doors[k], k, &panels);

  for (const WallDecoration& dec : world.decorations) {
    if (dec.wall_index != wi) continue;
    // Each layer a little further out, so overlapping marks never fight over depth.
    panels.Add(dec.offset_in, dec.offset_in + dec.width_in,
               kDecorationOffsetIn * (1.0 + 0.5 * std::max(0, dec.layer)), dec.bottom_in,
               dec.top_in, dec.intensity, wall.surface, PanelKind::kDecoration, -1, false);
  }
}

}  // namespace

Eigen::Vector2d Scene::Normal(const Panel& panel) {
  const Eigen::Vector2d d = (panel.p1_in - panel.p0_in).normalized();
  return {d.y(), -d.x()};
}

Scene::Scene(World world) : world_(std::move(world)) { Compile(); }

std::pair<Eigen::Vector2d, Eigen::Vector2d> Scene::JambPoints(int door_index) const {
  const DoorFeature& door = world_.doors.at(door_index);
  const WallSegment& wall = world_.walls.at(door.wall_index);
  const Eigen::Vector2d d = (wall.b_in - wall.a_in).normalized();
  const Eigen::Vector2d front = Eigen::Vector2d{d.y(), -d.x()} * kFrameOffsetIn;
  return {wall.a_in + d * door.offset_in + front,
          wall.a_in + d * (door.offset_in + door.width_in) + front};
}

void Scene::Compile() {
  CheckWorld(world_);
  const int n_walls = static_cast<int>(world_.walls.size());
  for (int wi = 0; wi < n_walls; ++wi) CompileWall(world_, wi, &panels_);
}

std::optional<RayHit> Scene::Raycast(const Eigen::Vector2d& origin_in,
                                     const Eigen::Vector2d& direction, double max_range_in,
                                     double height_in) const {
  const double norm = direction.norm();
  if (!(norm > 0.0)) return std::nullopt;
  const Eigen::Vector2d u = direction / norm;
  std::optional<RayHit> best;
  for (size_t i = 0; i < panels_.size(); ++i) {
    const Panel& p = panels_[i];
    if (!p.acoustic || !SpansHeight(p, height_in)) continue;
    const double t = Intersect(p, origin_in, u);
    if (t <= kMinT || t > max_range_in) continue;
    if (!best || t < best->distance_in) {
      RayHit hit;
      hit.distance_in = t;
      hit.point_in = origin_in + u * t;
      hit.surface = p.surface;
      hit.incidence_rad = std::acos(std::min(1.0, std::abs(u.dot(Normal(p)))));
      hit.panel_index = static_cast<int>(i);
      best = hit;
    }
  }
  return best;
}

std::optional<ConeHit> Scene::NearestInCone(const Eigen::Vector2d& apex_in,
                                            const Eigen::Vector2d& axis, double half_angle_rad,
                                            double max_range_in, double height_in) const {
  const double norm = axis.norm();
  if (!(norm > 0.0) || !(half_angle_rad > 0.0) || half_angle_rad >= 0.5 * kPi) {
    return std::nullopt;
  }
  const Eigen::Vector2d u = axis / norm;
  const Eigen::Vector2d u_left = Rotate(u, half_angle_rad);
  const Eigen::Vector2d u_right = Rotate(u, -half_angle_rad);
  std::optional<ConeHit> best;
  for (size_t i = 0; i < panels_.size(); ++i) {
    const Panel& p = panels_[i];
    if (!p.acoustic || !SpansHeight(p, height_in)) continue;
    const Eigen::Vector2d a = p.p0_in - apex_in;
    const Eigen::Vector2d e = p.p1_in - p.p0_in;
    // Clip a + lambda * e, lambda in [0, 1], to the wedge: counter-clockwise of u_right
    // and clockwise of u_left (Liang-Barsky on two half-planes through the apex).
    double lo = 0.0;
    double hi = 1.0;
    auto clip = [&](double c0, double c1) {  // keep c0 + lambda * c1 >= 0
      if (std::abs(c1) < 1e-15) {
        if (c0 < 0.0) hi = -1.0;
        return;
      }
      const double root = -c0 / c1;
      if (c1 > 0.0) {
        lo = std::max(lo, root);
      } else {
        hi = std::min(hi, root);
      }
    };
    clip(Cross(u_right, a), Cross(u_right, e));
    clip(-Cross(u_left, a), -Cross(u_left, e));
    if (lo > hi) continue;
    const double ee = e.squaredNorm();
    double lambda = ee > 0.0 ? -a.dot(e) / ee : lo;
    lambda = std::clamp(lambda, lo, hi);
    const Eigen::Vector2d q = a + e * lambda;
    const double dist = q.norm();
    if (dist <= kMinT || dist > max_range_in || q.dot(u) <= 0.0) continue;
    if (!best || dist < best->distance_in) {
      ConeHit hit;
      hit.distance_in = dist;
      hit.point_in = apex_in + q;
      hit.surface = p.surface;
      hit.incidence_rad = std::acos(std::min(1.0, std::abs(u.dot(Normal(p)))));
      hit.panel_index = static_cast<int>(i);
      best = hit;
    }
  }
  return best;
}

void Scene::CastAll(const Eigen::Vector2d& origin_in, const Eigen::Vector2d& direction,
                    double max_t, std::vector<Crossing>* out,
                    const std::vector<int>* subset) const {
  out->clear();
  const double dn = direction.norm();
  auto test = [&](int i) {
    const Panel& p = panels_[i];
    const double t = Intersect(p, origin_in, direction);
    if (t <= kMinT || t > max_t) return;
    const double c = std::abs(direction.dot(Normal(p))) / dn;
    out->push_back({t, i, c});
  };
  if (subset != nullptr) {
    for (int i : *subset) test(i);
  } else {
    for (size_t i = 0; i < panels_.size(); ++i) test(static_cast<int>(i));
  }
  std::sort(out->begin(), out->end(),
            [](const Crossing& a, const Crossing& b) { return a.t < b.t; });
}

std::vector<int> Scene::PanelsNear(const Eigen::Vector2d& center_in, const Eigen::Vector2d& forward,
                                   double max_range_in) const {
  std::vector<int> out;
  for (size_t i = 0; i < panels_.size(); ++i) {
    const Panel& p = panels_[i];
    const Eigen::Vector2d a = p.p0_in - center_in;
    const Eigen::Vector2d b = p.p1_in - center_in;
    if (a.dot(forward) <= 0.0 && b.dot(forward) <= 0.0) continue;
    const Eigen::Vector2d e = b - a;
    const double ee = e.squaredNorm();
    const double lambda = ee > 0.0 ? std::clamp(-a.dot(e) / ee, 0.0, 1.0) : 0.0;
    if ((a + e * lambda).norm() > max_range_in) continue;
    out.push_back(static_cast<int>(i));
  }
  return out;
}

}  // namespace stickrep::world
