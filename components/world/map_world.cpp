#include "world/map_world.h"

#include <algorithm>
#include <cmath>
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
  if (pattern.find("poster") != std::string::npos) return DoorPattern::kPoster;
  if (pattern.find("window") != std::string::npos && pattern.rfind("no_", 0) != 0) {
    return DoorPattern::kWindow;
  }
  return DoorPattern::kNone;
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

// Builds the rings listed in `ring_indices` into one world.
MapWorld Build(const map::Map& map, const std::vector<int>& ring_indices, OppositeWall opposite,
               const MapWorldOptions& options, std::mt19937_64& rng) {
  CheckOptions(options);
  MapWorld out;
  out.rings = ring_indices;
  World& world = out.world;
  world.ceiling_height_in = options.wall_height_in;
  std::uniform_real_distribution<double> unit(0.0, 1.0);

  struct PendingRoom {
    int wall_index;
    double s0_in, s1_in;  // door span along the wall, from its a_in end
  };
  std::vector<PendingRoom> rooms;
  std::vector<std::vector<WallRun>> runs_of_ring;

  for (int r : ring_indices) {
    const map::Ring& ring = map.ring(r);
    const std::vector<WallRun> runs = SplitIntoWallRuns(ring);
    runs_of_ring.push_back(runs);
    const size_t first_geometry = out.edges.size();
    out.edges.resize(first_geometry + ring.edges.size());
    for (const WallRun& run : runs) {
      const double length = run.length_in;
      // Position along the run (ring order) of a node: its projection on the run's line.
      auto along = [&](int node) {
        return std::clamp((NodePoint(ring, node) - run.start_in).dot(run.dir), 0.0, length);
      };
      const std::vector<int> run_edges = RunEdges(ring, run);
      // The run's wall, in pieces between its openings (map format 2: gaps the robot passes).
      // Each piece runs against ring order so that the hallway is on its right (world.h).
      // piece_end: where along the run the current piece ends; -1: no piece open.
      int wall_index = -1;
      double piece_start = 0.0, piece_end = 0.0;
      auto open_piece = [&](size_t from) {
        piece_start = from == 0 ? 0.0 : along(run_edges[from]);
        piece_end = length;
        for (size_t k = from; k < run_edges.size(); ++k) {
          if (ring.edges[run_edges[k]].IsOpening()) {
            piece_end = along(run_edges[k]);
            break;
          }
        }
        wall_index = static_cast<int>(world.walls.size());
        WallSegment wall;
        wall.a_in = run.start_in + run.dir * piece_end;
        wall.b_in = run.start_in + run.dir * piece_start;
        wall.height_in = options.wall_height_in;
        wall.surface = options.wall_surface;
        wall.intensity = options.wall_intensity;
        world.walls.push_back(wall);
        out.wall_ring.push_back(r);
      };
      for (size_t k = 0; k < run_edges.size(); ++k) {
        const int e = run_edges[k];
        const map::Edge& edge = ring.edges[e];
        const double s0 = along(e);
        const double s1 = (e == run.last) ? length : along(e + 1);
        MapEdgeGeometry& g = out.edges[first_geometry + e];
        g.ref = {r, e};
        g.start_in = NodePoint(ring, e);
        g.end_in = NodePoint(ring, e + 1);
        g.metric_in = edge.metric_in;
        if (edge.IsOpening()) {
          wall_index = -1;  // nothing is built across an opening
          continue;
        }
        if (wall_index < 0) open_piece(k);
        g.wall_index = wall_index;
        // Centre a feature of width w on the edge's span; in wall coordinates (from a_in).
        auto wall_offset = [&](double w) {
          const double centre = 0.5 * (s0 + s1);
          const double ring_offset =
              std::clamp(centre - w / 2.0, piece_start, std::max(piece_start, piece_end - w));
          return piece_end - (ring_offset + w);
        };
        const bool door_like = edge.IsDoor() || edge.type == map::EdgeType::kElevator ||
                               edge.type == map::EdgeType::kStairwell;
        if (door_like) {
          DoorFeature door = options.door_template;
          door.wall_index = wall_index;
          // The measured opening (map format 2), or the class width (format 1 doors carry it
          // as their metric).
          door.width_in = std::min(edge.metric_in, piece_end - piece_start);
          door.offset_in = wall_offset(door.width_in);
          door.double_door = door.width_in > kDoubleDoorMinWidthIn;
          door.pattern = DoorPatternOf(edge.pattern);
          door.state = DoorState::kClosed;
          door.open_angle_rad = 0.0;
          if (edge.IsDoor() && options.open_door_fraction > 0.0) {
            // Draw all four numbers for every door so a door's state does not depend on
            // the states before it.
            const double u_open = unit(rng), u_in = unit(rng), u_angle = unit(rng),
                         u_hinge = unit(rng);
            if (u_open < options.open_door_fraction) {
              door.state = u_in < options.open_inward_share ? DoorState::kOpenInward
                                                            : DoorState::kOpenOutward;
              door.open_angle_rad =
                  DegToRad(options.min_open_angle_deg +
                           u_angle * (options.max_open_angle_deg - options.min_open_angle_deg));
              door.hinge_at_start = u_hinge < 0.5;
            }
          }
          g.door_index = static_cast<int>(world.doors.size());
          world.doors.push_back(door);
          out.door_edges.push_back({r, e});
          rooms.push_back({wall_index, door.offset_in, door.offset_in + door.width_in});
          continue;
        }
        if (edge.pattern.empty()) continue;
        WallDecoration mark;
        mark.wall_index = wall_index;
        const double span = std::max(0.0, s1 - s0);
        if (edge.pattern.find("poster") != std::string::npos) {
          mark.width_in = std::min(options.poster_width_in, 0.6 * span);
          mark.intensity = options.poster_intensity;
        } else if (edge.pattern.find("ribbon") != std::string::npos) {
          // §6.8: "a single artificial vertical edge ribbon": the whole edge, floor to
          // door height, dark against the wall.
          mark.width_in = span;
          mark.bottom_in = world.baseboard_height_in;
          mark.top_in = options.door_template.height_in;
          mark.intensity = options.ribbon_intensity;
        } else if (edge.pattern.find("window") != std::string::npos &&
                   edge.pattern.rfind("no_", 0) != 0) {
          mark.width_in = 0.6 * span;
          mark.bottom_in = 36.0;
          mark.top_in = 80.0;
          mark.intensity = options.window_intensity;
        } else {
          continue;  // a mark the camera cannot be told how to draw
        }
        if (mark.width_in <= 0.0) continue;
        mark.offset_in = wall_offset(mark.width_in);
        world.decorations.push_back(mark);
      }
    }
  }

  // The opposite hallway walls: parallel to each ring at the hallway width. A shallow step
  // of the mapped wall (a pilaster, an alcove) is that wall's own: the opposite wall runs
  // straight past it.
  // Obstacles (columns, piers): closed outlines, faces outward.
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
      world.walls.push_back(wall);
      out.wall_ring.push_back(-1);
    }
  }

  // Only side rings face a wall that is not in the map; a corridor outline has both sides.
  for (size_t k = 0; k < ring_indices.size(); ++k) {
    const map::Ring& ring = map.ring(ring_indices[k]);
    const bool add = ring.outline == map::Outline::kSide &&
                     (opposite == OppositeWall::kAlways ||
                      (opposite == OppositeWall::kAuto &&
                       (ring_indices.size() == 1 || ring.width_in.has_value())));
    if (!add) continue;
    {
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
        world.walls.push_back(wall);
        out.wall_ring.push_back(-1);
        ++out.opposite_wall_count;
      }
    }
  }

  // Back walls of the rooms behind the doors, clipped against every mapped wall behind.
  for (const PendingRoom& room : rooms) {
    const WallSegment wall = world.walls[room.wall_index];
    const Eigen::Vector2d d = (wall.b_in - wall.a_in).normalized();
    const Eigen::Vector2d into_room{-d.y(), d.x()};  // left of a -> b: away from the hallway
    const double s0 = room.s0_in - kRoomBackWallMarginIn;
    const double s1 = room.s1_in + kRoomBackWallMarginIn;
    double depth = options.room_depth_in;
    for (double s : {s0, 0.5 * (s0 + s1), s1}) {
      const Eigen::Vector2d origin = wall.a_in + d * s + into_room * 0.5;
      for (const MapEdgeGeometry& g : out.edges) {
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
    out.wall_ring.push_back(-1);
  }
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
