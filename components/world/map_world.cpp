#include "world/map_world.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "common/units.h"

namespace stickrep::world {
namespace {

// Consecutive edges whose directions differ by less than this lie on one wall.
constexpr double kCollinearRad = DegToRad(0.5);
// An offset segment shorter than this has collapsed (a pilaster or an alcove narrower than
// the hallway): the opposite wall skips it.
constexpr double kMinOffsetSegmentIn = 1.0;
// Half-width added on each side of a door to the room's back wall.
constexpr double kRoomBackWallMarginIn = 24.0;
// Gap kept between a room's back wall and any other mapped wall behind it.
constexpr double kRoomClearanceIn = 2.0;
// Doors wider than this are drawn as two leaves (30/30 and 36/36, §4.1.2).
constexpr double kDoubleDoorMinWidthIn = 50.0;

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Left of a direction: the hallway side of a ring edge.
Eigen::Vector2d Left(const Eigen::Vector2d& d) { return {-d.y(), d.x()}; }

// Distance along the ray origin + t u (u unit) to the segment p-q, or infinity.
double RayToSegment(const Eigen::Vector2d& origin, const Eigen::Vector2d& u,
                    const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
  const Eigen::Vector2d e = q - p;
  const double denom = Cross(u, e);
  if (std::abs(denom) < 1e-12) return std::numeric_limits<double>::infinity();
  const Eigen::Vector2d w = p - origin;
  const double t = Cross(w, e) / denom;
  const double s = Cross(w, u) / denom;
  if (t <= 0.0 || s < 0.0 || s > 1.0) return std::numeric_limits<double>::infinity();
  return t;
}

Eigen::Vector2d NodePoint(const map::Ring& ring, int node) {
  const map::Node& n = ring.nodes[static_cast<size_t>(node) % ring.nodes.size()];
  return {n.x_in, n.y_in};
}

}  // namespace

std::vector<WallRun> SplitIntoWallRuns(const map::Ring& ring) {
  const int n = ring.EdgeCount();
  std::vector<Eigen::Vector2d> dir(n);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d e = NodePoint(ring, i + 1) - NodePoint(ring, i);
    if (e.norm() < 1e-6) {
      throw std::invalid_argument("ring '" + ring.id + "': edge " + std::to_string(i) +
                                  " has coincident nodes");
    }
    dir[i] = e.normalized();
  }
  auto turns = [&](int i, int j) {
    return std::abs(std::atan2(Cross(dir[i], dir[j]), dir[i].dot(dir[j]))) > kCollinearRad;
  };
  int start = 0;
  if (ring.closed) {
    // Begin at an edge that follows a corner, if the ring has one.
    for (int i = 0; i < n; ++i) {
      if (turns((i + n - 1) % n, i)) {
        start = i;
        break;
      }
    }
  }
  std::vector<WallRun> runs;
  WallRun current;
  current.first = start;
  for (int k = 0; k < n; ++k) {
    const int i = (start + k) % n;
    const bool last_edge = k == n - 1;
    const bool corner_after = last_edge || turns(i, (i + 1) % n);
    if (corner_after) {
      current.last = i;
      runs.push_back(current);
      current = WallRun{};
      current.first = (i + 1) % n;
    }
  }
  for (WallRun& r : runs) {
    r.start_in = NodePoint(ring, r.first);
    // A run may wrap past the last edge of a closed ring.
    r.end_in = NodePoint(ring, r.last + 1);
    r.length_in = (r.end_in - r.start_in).norm();
    r.dir = (r.end_in - r.start_in) / r.length_in;
  }
  return runs;
}

std::vector<WallRun> WithoutSteps(std::vector<WallRun> runs, bool closed, double max_step_in) {
  // cos 5°: the runs either side of a step are parallel, the same way.
  constexpr double kParallelCos = 0.996;
  for (bool changed = true; changed;) {
    changed = false;
    const int m = static_cast<int>(runs.size());
    if (m < 3) break;
    for (int j = 0; j < m; ++j) {
      if (!closed && (j == 0 || j == m - 1)) continue;
      const int before = (j + m - 1) % m, after = (j + 1) % m;
      const WallRun& prev = runs[before];
      const WallRun& next = runs[after];
      if (runs[j].length_in >= max_step_in || prev.dir.dot(next.dir) < kParallelCos) continue;
      // One run on the longer neighbour's line, from abreast of prev's start to abreast of
      // next's end.
      const WallRun& keep = prev.length_in >= next.length_in ? prev : next;
      WallRun merged;
      merged.first = prev.first;
      merged.last = next.last;
      merged.dir = keep.dir;
      merged.start_in = keep.start_in + keep.dir * (prev.start_in - keep.start_in).dot(keep.dir);
      merged.end_in = keep.start_in + keep.dir * (next.end_in - keep.start_in).dot(keep.dir);
      merged.length_in = (merged.end_in - merged.start_in).dot(merged.dir);
      // Replace prev, the step and next (which may wrap round a closed ring) by the merge.
      std::vector<WallRun> out;
      for (int k = 0; k < m; ++k) {
        if (k == before) {
          out.push_back(merged);
        } else if (k != j && k != after) {
          out.push_back(runs[k]);
        }
      }
      if (after < before) {
        // The merge wrapped: keep the ring's run order starting after it.
        std::rotate(out.begin(), out.end() - 1, out.end());
      }
      runs = std::move(out);
      changed = true;
      break;
    }
  }
  return runs;
}

std::vector<OffsetSegment> OffsetRuns(const std::vector<WallRun>& all_runs, bool closed,
                                      double distance_in) {
  struct Indexed {
    WallRun run;
    int index;
  };
  std::vector<Indexed> runs;
  for (int i = 0; i < static_cast<int>(all_runs.size()); ++i) runs.push_back({all_runs[i], i});
  auto offset_point = [&](const WallRun& r) -> Eigen::Vector2d {
    return r.start_in + Left(r.dir) * distance_in;
  };
  // Vertex between offset lines of runs a and b (b follows a).
  auto mitre = [&](const WallRun& a, const WallRun& b) -> Eigen::Vector2d {
    const Eigen::Vector2d pa = offset_point(a);
    const Eigen::Vector2d pb = offset_point(b);
    const double denom = Cross(a.dir, b.dir);
    if (std::abs(denom) < 1e-9) {
      // Parallel lines: the shared node's offset along b's normal.
      return b.start_in + Left(b.dir) * distance_in;
    }
    const double t = Cross(pb - pa, b.dir) / denom;
    return pa + a.dir * t;
  };
  std::vector<OffsetSegment> segments;
  for (int guard = 0; guard < 10000; ++guard) {
    const int m = static_cast<int>(runs.size());
    // Two runs left of a closed ring: the two sides of a straight corridor outline, whose
    // offset lines meet on its axis (antiparallel: the mitres are the runs' own ends).
    if (m == 0 || (closed && m < 2)) return {};
    segments.clear();
    int collapsed = -1;
    for (int j = 0; j < m; ++j) {
      const WallRun& run = runs[j].run;
      Eigen::Vector2d a, b;
      if (j == 0 && !closed) {
        a = offset_point(run);
      } else {
        a = mitre(runs[(j + m - 1) % m].run, run);
      }
      if (j == m - 1 && !closed) {
        b = run.end_in + Left(run.dir) * distance_in;
      } else {
        b = mitre(run, runs[(j + 1) % m].run);
      }
      if ((b - a).dot(run.dir) < kMinOffsetSegmentIn) {
        collapsed = j;
        break;
      }
      segments.push_back({a, b, runs[j].index});
    }
    if (collapsed < 0) return segments;
    runs.erase(runs.begin() + collapsed);
  }
  return {};
}

namespace {

// The edges of a run in order (handles wrap-around on closed rings).
std::vector<int> RunEdges(const map::Ring& ring, const WallRun& run) {
  std::vector<int> out;
  const int n = ring.EdgeCount();
  for (int i = run.first;; i = (i + 1) % n) {
    out.push_back(i);
    if (i == run.last) break;
  }
  return out;
}

DoorPattern DoorPatternOf(const std::string& pattern) {
  switch (map::DoorMarkOfPattern(pattern)) {
    case map::DoorMark::kPoster: return DoorPattern::kPoster;
    case map::DoorMark::kWindow: return DoorPattern::kWindow;
    default: return DoorPattern::kNone;
  }
}

void CheckOptions(const MapWorldOptions& o) {
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive(o.hallway_width_in) || !positive(o.wall_height_in) || !positive(o.room_depth_in) ||
      !positive(o.poster_width_in)) {
    throw std::invalid_argument(
        "map world: hallway_width_in, wall_height_in, room_depth_in and poster_width_in must be "
        "> 0 in");
  }
  if (!(o.opposite_wall_max_step_in >= 0.0)) {
    throw std::invalid_argument("map world: opposite_wall_max_step_in must be >= 0 in");
  }
  if (!(o.open_door_fraction >= 0.0 && o.open_door_fraction <= 1.0) ||
      !(o.open_inward_share >= 0.0 && o.open_inward_share <= 1.0)) {
    throw std::invalid_argument(
        "map world: open_door_fraction and open_inward_share must lie in [0, 1]");
  }
  if (!(o.min_open_angle_deg >= 0.0 && o.min_open_angle_deg <= o.max_open_angle_deg &&
        o.max_open_angle_deg <= 110.0)) {
    throw std::invalid_argument(
        "map world: need 0 <= min_open_angle_deg <= max_open_angle_deg <= 110 deg");
  }
}

// A door span whose room is built once every wall is in: the room's back wall is clipped
// against all of them.
struct PendingRoom {
  int wall_index;
  double s0_in, s1_in;  // door span along the wall, from its a_in end
};

// One piece of a run's wall, between its openings (map format 2: gaps the robot passes), as
// positions along the run (ring order).
struct WallPiece {
  int wall_index = -1;  // -1: no piece open
  double start = 0.0;
  double end = 0.0;
};

// Position along the run (ring order) of a node: its projection on the run's line.
double AlongRun(const map::Ring& ring, const WallRun& run, int node) {
  return std::clamp((NodePoint(ring, node) - run.start_in).dot(run.dir), 0.0, run.length_in);
}

// Centre a feature of width w on an edge's span [s0, s1] of the piece; in wall coordinates
// (from a_in).
double WallOffset(const WallPiece& piece, double s0, double s1, double w) {
  const double centre = 0.5 * (s0 + s1);
  const double ring_offset =
      std::clamp(centre - w / 2.0, piece.start, std::max(piece.start, piece.end - w));
  return piece.end - (ring_offset + w);
}

// Edges drawn as a door: doorways, and elevators and stairwells as closed doors.
bool IsDoorLike(const map::Edge& edge) {
  return edge.IsDoor() || edge.type == map::EdgeType::kElevator ||
         edge.type == map::EdgeType::kStairwell;
}

// The mark a non-door edge's pattern asks for on the piece (Table 6.8 marks, §6.8 ribbon),
// or none.
std::optional<WallDecoration> MakeMark(const map::Edge& edge, const WallPiece& piece, double s0,
                                       double s1, const MapWorldOptions& options,
                                       double baseboard_height_in) {
  if (edge.pattern.empty()) return std::nullopt;
  WallDecoration mark;
  mark.wall_index = piece.wall_index;
  const double span = std::max(0.0, s1 - s0);
  if (edge.pattern.find("poster") != std::string::npos) {
    mark.width_in = std::min(options.poster_width_in, 0.6 * span);
    mark.intensity = options.poster_intensity;
  } else if (edge.pattern.find("ribbon") != std::string::npos) {
    // §6.8: "a single artificial vertical edge ribbon": the whole edge, floor to
    // door height, dark against the wall.
    mark.width_in = span;
    mark.bottom_in = baseboard_height_in;
    mark.top_in = options.door_template.height_in;
    mark.intensity = options.ribbon_intensity;
  } else if (edge.pattern.find("window") != std::string::npos &&
             edge.pattern.rfind("no_", 0) != 0) {
    mark.width_in = 0.6 * span;
    mark.bottom_in = 36.0;
    mark.top_in = 80.0;
    mark.intensity = options.window_intensity;
  } else {
    return std::nullopt;  // a mark the camera cannot be told how to draw
  }
  if (mark.width_in <= 0.0) return std::nullopt;
  mark.offset_in = WallOffset(piece, s0, s1, mark.width_in);
  return mark;
}

// Adds the rings' own walls, with their doors and marks, to a MapWorld (Build's first step)
// and keeps the door spans whose rooms come last. Door states are drawn from one
// distribution over `rng`, in ring and edge order.
class RingBuilder {
 public:
  RingBuilder(const MapWorldOptions& options, std::mt19937_64& rng, MapWorld* out)
      : options_(options), rng_(rng), out_(out) {}

  // Ring r, split into `runs`: each run becomes one wall, in pieces between its openings.
  void AddRing(const map::Ring& ring, int r, const std::vector<WallRun>& runs);

  const std::vector<PendingRoom>& rooms() const { return rooms_; }

 private:
  // One run: its wall pieces, doors and marks, and the geometry of its edges (from
  // out_->edges[first_geometry], the ring's first).
  void AddRun(const map::Ring& ring, int r, const WallRun& run, size_t first_geometry);
  WallPiece OpenPiece(const map::Ring& ring, int r, const WallRun& run,
                      const std::vector<int>& run_edges, size_t from);
  // A door (elevators and stairwells too) centred on its edge's span [s0, s1] of the piece.
  DoorFeature MakeDoor(const map::Edge& edge, const WallPiece& piece, double s0, double s1);
  // Opens a doorway with the odds of MapWorldOptions.
  void DrawDoorState(DoorFeature* door);

  const MapWorldOptions& options_;
  std::mt19937_64& rng_;
  std::uniform_real_distribution<double> unit_{0.0, 1.0};
  MapWorld* out_;
  std::vector<PendingRoom> rooms_;
};

void RingBuilder::AddRing(const map::Ring& ring, int r, const std::vector<WallRun>& runs) {
  const size_t first_geometry = out_->edges.size();
  out_->edges.resize(first_geometry + ring.edges.size());
  for (const WallRun& run : runs) AddRun(ring, r, run, first_geometry);
}

void RingBuilder::AddRun(const map::Ring& ring, int r, const WallRun& run, size_t first_geometry) {
  World& world = out_->world;
  const std::vector<int> run_edges = RunEdges(ring, run);
  WallPiece piece;
  for (size_t k = 0; k < run_edges.size(); ++k) {
    const int e = run_edges[k];
    const map::Edge& edge = ring.edges[e];
    const double s0 = AlongRun(ring, run, e);
    const double s1 = (e == run.last) ? run.length_in : AlongRun(ring, run, e + 1);
    MapEdgeGeometry& g = out_->edges[first_geometry + e];
    g.ref = {r, e};
    g.start_in = NodePoint(ring, e);
    g.end_in = NodePoint(ring, e + 1);
    g.metric_in = edge.metric_in;
    if (edge.IsOpening()) {
      piece.wall_index = -1;  // nothing is built across an opening
      continue;
    }
    if (piece.wall_index < 0) piece = OpenPiece(ring, r, run, run_edges, k);
    g.wall_index = piece.wall_index;
    if (IsDoorLike(edge)) {
      const DoorFeature door = MakeDoor(edge, piece, s0, s1);
      g.door_index = static_cast<int>(world.doors.size());
      world.doors.push_back(door);
      out_->door_edges.push_back({r, e});
      rooms_.push_back({piece.wall_index, door.offset_in, door.offset_in + door.width_in});
      continue;
    }
    const std::optional<WallDecoration> mark =
        MakeMark(edge, piece, s0, s1, options_, world.baseboard_height_in);
    if (mark) world.decorations.push_back(*mark);
  }
}

// The piece from run edge `from` to the next opening (or the run's end). It runs against
// ring order so that the hallway is on its right (world.h).
WallPiece RingBuilder::OpenPiece(const map::Ring& ring, int r, const WallRun& run,
                                 const std::vector<int>& run_edges, size_t from) {
  WallPiece piece;
  piece.start = from == 0 ? 0.0 : AlongRun(ring, run, run_edges[from]);
  piece.end = run.length_in;
  for (size_t k = from; k < run_edges.size(); ++k) {
    if (ring.edges[run_edges[k]].IsOpening()) {
      piece.end = AlongRun(ring, run, run_edges[k]);
      break;
    }
  }
  piece.wall_index = static_cast<int>(out_->world.walls.size());
  WallSegment wall;
  wall.a_in = run.start_in + run.dir * piece.end;
  wall.b_in = run.start_in + run.dir * piece.start;
  wall.height_in = options_.wall_height_in;
  wall.surface = options_.wall_surface;
  wall.intensity = options_.wall_intensity;
  out_->world.walls.push_back(wall);
  out_->wall_ring.push_back(r);
  return piece;
}

DoorFeature RingBuilder::MakeDoor(const map::Edge& edge, const WallPiece& piece, double s0,
                                  double s1) {
  DoorFeature door = options_.door_template;
  door.wall_index = piece.wall_index;
  // The measured opening (map format 2), or the class width (format 1 doors carry it
  // as their metric).
  door.width_in = std::min(edge.metric_in, piece.end - piece.start);
  door.offset_in = WallOffset(piece, s0, s1, door.width_in);
  door.double_door = door.width_in > kDoubleDoorMinWidthIn;
  door.pattern = DoorPatternOf(edge.pattern);
  door.state = DoorState::kClosed;
  door.open_angle_rad = 0.0;
  if (edge.IsDoor() && options_.open_door_fraction > 0.0) DrawDoorState(&door);
  return door;
}

void RingBuilder::DrawDoorState(DoorFeature* door) {
  // Draw all four numbers for every door so a door's state does not depend on
  // the states before it.
  const double u_open = unit_(rng_), u_in = unit_(rng_), u_angle = unit_(rng_),
               u_hinge = unit_(rng_);
  if (u_open < options_.open_door_fraction) {
    door->state =
        u_in < options_.open_inward_share ? DoorState::kOpenInward : DoorState::kOpenOutward;
    door->open_angle_rad =
        DegToRad(options_.min_open_angle_deg +
                 u_angle * (options_.max_open_angle_deg - options_.min_open_angle_deg));
    door->hinge_at_start = u_hinge < 0.5;
  }
}

// Obstacles (columns, piers): closed outlines, faces outward.
void AddObstacleWalls(const map::Map& map, const MapWorldOptions& options, MapWorld* out) {
  for (const map::Obstacle& o : map.obstacles()) {
    const size_t n = o.polygon_in.size();
    double area2 = 0.0;
    for (size_t i = 0; i < n; ++i) {
      const auto& p = o.polygon_in[i];
      const auto& q = o.polygon_in[(i + 1) % n];
      area2 += p[0] * q[1] - q[0] * p[1];
    }
    // Counter-clockwise, a wall from corner i to i + 1 has the outside on its right.
    for (size_t k = 0; k < n; ++k) {
      const size_t i = area2 >= 0.0 ? k : n - 1 - k;
      const size_t j = area2 >= 0.0 ? (k + 1) % n : (2 * n - 2 - k) % n;
      WallSegment wall;
      wall.a_in = {o.polygon_in[i][0], o.polygon_in[i][1]};
      wall.b_in = {o.polygon_in[j][0], o.polygon_in[j][1]};
      wall.height_in = options.wall_height_in;
      wall.surface = options.wall_surface;
      wall.intensity = options.wall_intensity;
      out->world.walls.push_back(wall);
      out->wall_ring.push_back(-1);
    }
  }
}

// The opposite hallway walls: parallel to each ring at the hallway width. A shallow step
// of the mapped wall (a pilaster, an alcove) is that wall's own: the opposite wall runs
// straight past it. `runs_of_ring[k]` are the runs of ring ring_indices[k].
void AddOppositeWalls(const map::Map& map, const std::vector<int>& ring_indices,
                      const std::vector<std::vector<WallRun>>& runs_of_ring, OppositeWall opposite,
                      const MapWorldOptions& options, MapWorld* out) {
  // Only side rings face a wall that is not in the map; a corridor outline has both sides.
  for (size_t k = 0; k < ring_indices.size(); ++k) {
    const map::Ring& ring = map.ring(ring_indices[k]);
    const bool add = ring.outline == map::Outline::kSide &&
                     (opposite == OppositeWall::kAlways ||
                      (opposite == OppositeWall::kAuto &&
                       (ring_indices.size() == 1 || ring.width_in.has_value())));
    if (!add) continue;
    const double width = ring.width_in.value_or(options.hallway_width_in);
    const std::vector<WallRun> straight =
        WithoutSteps(runs_of_ring[k], ring.closed, options.opposite_wall_max_step_in);
    for (const OffsetSegment& s : OffsetRuns(straight, ring.closed, width)) {
      // In ring order the mapped wall is on this wall's right: the hallway is there.
      WallSegment wall;
      wall.a_in = s.a_in;
      wall.b_in = s.b_in;
      wall.height_in = options.wall_height_in;
      wall.surface = options.opposite_surface;
      wall.intensity = options.opposite_wall_intensity;
      out->world.walls.push_back(wall);
      out->wall_ring.push_back(-1);
      ++out->opposite_wall_count;
    }
  }
}

// Back walls of the rooms behind the doors, clipped against every mapped wall behind.
void AddRoomBackWalls(const std::vector<PendingRoom>& rooms, const MapWorldOptions& options,
                      MapWorld* out) {
  World& world = out->world;
  for (const PendingRoom& room : rooms) {
    const WallSegment wall = world.walls[room.wall_index];
    const Eigen::Vector2d d = (wall.b_in - wall.a_in).normalized();
    const Eigen::Vector2d into_room{-d.y(), d.x()};  // left of a -> b: away from the hallway
    const double s0 = room.s0_in - kRoomBackWallMarginIn;
    const double s1 = room.s1_in + kRoomBackWallMarginIn;
    double depth = options.room_depth_in;
    for (double s : {s0, 0.5 * (s0 + s1), s1}) {
      const Eigen::Vector2d origin = wall.a_in + d * s + into_room * 0.5;
      for (const MapEdgeGeometry& g : out->edges) {
        if (g.wall_index == room.wall_index) continue;
        depth = std::min(
            depth, RayToSegment(origin, into_room, g.start_in, g.end_in) + 0.5 - kRoomClearanceIn);
      }
    }
    if (depth < 12.0) continue;  // no room for a room: the opening shows nothing behind
    WallSegment back;
    back.a_in = wall.a_in + d * s0 + into_room * depth;
    back.b_in = wall.a_in + d * s1 + into_room * depth;
    back.height_in = options.wall_height_in;
    back.surface = options.wall_surface;
    back.intensity = options.room_wall_intensity;
    world.walls.push_back(back);
    out->wall_ring.push_back(-1);
  }
}

// Builds the rings listed in `ring_indices` into one world.
MapWorld Build(const map::Map& map, const std::vector<int>& ring_indices, OppositeWall opposite,
               const MapWorldOptions& options, std::mt19937_64& rng) {
  CheckOptions(options);
  MapWorld out;
  out.rings = ring_indices;
  out.world.ceiling_height_in = options.wall_height_in;
  RingBuilder builder(options, rng, &out);
  std::vector<std::vector<WallRun>> runs_of_ring;
  for (int r : ring_indices) {
    const map::Ring& ring = map.ring(r);
    runs_of_ring.push_back(SplitIntoWallRuns(ring));
    builder.AddRing(ring, r, runs_of_ring.back());
  }
  AddObstacleWalls(map, options, &out);
  AddOppositeWalls(map, ring_indices, runs_of_ring, opposite, options, &out);
  AddRoomBackWalls(builder.rooms(), options, &out);
  return out;
}

}  // namespace

MapWorld BuildRingWorld(const map::Map& map, int ring, const MapWorldOptions& options,
                        std::mt19937_64& rng) {
  if (ring < 0 || ring >= map.RingCount()) {
    throw std::invalid_argument("map world: ring index " + std::to_string(ring) +
                                " out of range (map has " + std::to_string(map.RingCount()) +
                                " rings)");
  }
  const OppositeWall opposite =
      options.opposite_wall == OppositeWall::kNever ? OppositeWall::kNever : OppositeWall::kAlways;
  return Build(map, {ring}, opposite, options, rng);
}

MapWorld BuildMapWorld(const map::Map& map, const MapWorldOptions& options, std::mt19937_64& rng) {
  std::vector<int> rings;
  for (int r = 0; r < map.RingCount(); ++r) rings.push_back(r);
  return Build(map, rings, options.opposite_wall, options, rng);
}

std::optional<MapPlace> LocateOnMap(const MapWorld& world, const Eigen::Vector2d& p_W_in,
                                    double max_distance_in) {
  std::optional<MapPlace> best;
  for (const MapEdgeGeometry& g : world.edges) {
    const Eigen::Vector2d e = g.end_in - g.start_in;
    const double len2 = e.squaredNorm();
    if (len2 <= 0.0) continue;
    const double t = std::clamp((p_W_in - g.start_in).dot(e) / len2, 0.0, 1.0);
    const double dist = (p_W_in - (g.start_in + e * t)).norm();
    if (dist > max_distance_in) continue;
    if (!best || dist < best->distance_in) {
      best = MapPlace{g.ref, t * g.metric_in, dist};
    }
  }
  return best;
}

}  // namespace stickrep::world
