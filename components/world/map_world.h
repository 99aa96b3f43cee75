#pragma once

#include <Eigen/Core>
#include <limits>
#include <optional>
#include <random>
#include <vector>

#include "stickrep/map.h"
#include "world/world.h"

namespace stickrep::world {

// Whether a hallway wall is added opposite the mapped walls of a side ring (map::Outline;
// a corridor outline has both sides and never gets one). Its distance is the ring's
// width_in when the map gives it, else MapWorldOptions::hallway_width_in.
enum class OppositeWall {
  // When a single ring is built, and for rings whose width the map gives: a ring on its own
  // faces nothing, while the rings of a whole floor face each other across their hallways
  // (a corridor ring round a block ring).
  kAuto,
  kAlways,
  kNever,
};

// How a StickRep map becomes a simulated building. The geometry comes from the map: the
// node coordinates place the walls, the edge metrics and door classes size the doors. The
// rest is not in the map and takes the defaults of MakeStraightHallway.
struct MapWorldOptions {
  // Distance from a mapped wall to the opposite wall it faces (when one is added).
  double hallway_width_in = 72.0;  // not in the text: a 6 ft corridor, as HallwayOptions
  OppositeWall opposite_wall = OppositeWall::kAuto;
  // Steps of the mapped wall shorter than this (WithoutSteps) do not show in the opposite
  // wall: 36 in, as map::HallwayViewConfig::max_step_in.
  double opposite_wall_max_step_in = 36.0;
  double wall_height_in = 96.0;
  // Depth of the room behind a door (its back wall is what an open door shows). Clipped so
  // the back wall stays inside the solid behind the ring.
  double room_depth_in = 144.0;
  SurfaceType wall_surface = SurfaceType::kConcrete;
  SurfaceType opposite_surface = SurfaceType::kConcrete;
  int wall_intensity = 175;
  int opposite_wall_intensity = 160;
  int room_wall_intensity = 110;
  DoorFeature door_template;  // frame (casing), leaf, height of every door

  // Door states, drawn from the caller's generator (seeded): each doorway is open with
  // probability open_door_fraction; an open door swings into the room with probability
  // open_inward_share, else into the hallway, by an angle uniform in the range below, and
  // its hinge is on either jamb with equal odds. 0 leaves every door closed.
  double open_door_fraction = 0.0;
  double open_inward_share = 0.5;
  double min_open_angle_deg = 15.0;
  double max_open_angle_deg = 100.0;

  // Marks for edge patterns that are not doors (Table 6.8 marks, §6.8 artificial ribbon).
  double poster_width_in = 24.0;
  int poster_intensity = 230;
  int window_intensity = 215;
  int ribbon_intensity = 60;  // a dark full-height strip: a vertical edge ribbon by design
};

// A straight run of ring edges [first, last] (ring-local indices, ring order; on a closed
// ring the run may wrap past the last edge) and its line.
struct WallRun {
  int first = 0;
  int last = 0;
  Eigen::Vector2d start_in{0.0, 0.0};  // node `first` (or abreast of it, after WithoutSteps)
  Eigen::Vector2d end_in{0.0, 0.0};    // node `last + 1` (or abreast of it)
  Eigen::Vector2d dir{1.0, 0.0};       // unit, start -> end
  double length_in = 0.0;
};

// Splits a ring into straight runs of collinear edges. A closed ring's first run starts
// after its first corner so that no run wraps. Throws std::invalid_argument for an edge
// whose nodes coincide.
std::vector<WallRun> SplitIntoWallRuns(const map::Ring& ring);

// The runs as a hallway follower passes them: a run shorter than `max_step_in` between two
// runs going the same way (a step across the hallway: a pilaster, an alcove) is dropped and
// its neighbours become one run on the line of the longer of them. Repeats until no such
// step is left (an alcove's two steps go one after the other).
std::vector<WallRun> WithoutSteps(std::vector<WallRun> runs, bool closed, double max_step_in);

// One segment of a polyline parallel to a ring's runs, and the run it is parallel to.
struct OffsetSegment {
  Eigen::Vector2d a_in{0.0, 0.0};
  Eigen::Vector2d b_in{0.0, 0.0};
  int run = 0;  // index into the runs given
};

// The polyline parallel to `runs` at `distance_in` on their hallway side (left of ring
// order), in ring order. Corners are mitred; a segment that collapses (shorter than an inch
// or reversed, as the offset of a narrow pilaster or alcove is) is dropped and its
// neighbours re-mitred, the usual way of offsetting a polygon. Empty when nothing is left.
std::vector<OffsetSegment> OffsetRuns(const std::vector<WallRun>& runs, bool closed,
                                      double distance_in);

// A map edge: ring index and edge index within the ring.
struct MapEdgeRef {
  int ring = -1;
  int edge = -1;
};

// Where one map edge lies in the world, in ring order (start node -> end node).
struct MapEdgeGeometry {
  MapEdgeRef ref;
  Eigen::Vector2d start_in{0.0, 0.0};
  Eigen::Vector2d end_in{0.0, 0.0};
  double metric_in = 0.0;
  int wall_index = -1;  // the world wall that carries it
  int door_index = -1;  // the world door drawn for it, or -1
};

// A World built from a map, with the bookkeeping that ties world parts back to map edges
// (ground truth for the simulation and the measurement tools).
struct MapWorld {
  World world;
  std::vector<int> rings;              // the rings built, by index into map.rings()
  std::vector<MapEdgeGeometry> edges;  // every edge of every built ring, ring by ring
  std::vector<MapEdgeRef> door_edges;  // world.doors[k] is the map edge door_edges[k]
  std::vector<int> wall_ring;          // ring of world.walls[i]; -1 opposite and room walls
  int opposite_wall_count = 0;
};

// One ring of `map` as a world: each straight run of edges (consecutive edges on one line)
// becomes one wall, its doors and marks set into it at their edge positions; the hallway
// side is on the left of the ring's direction (maps/README.md: edges are listed walking with
// the wall on the right). Doorways get their metric width (double doors as two leaves),
// patterns become leaf windows or posters on doors and posters, windows or a dark ribbon on
// other edges; elevators and stairwells are drawn as closed doors of their metric width.
// Doors are as wide as their metric (the measured width in map format 2); nothing is built
// across an `opening` edge: the run's wall stops either side of it.
// Throws std::invalid_argument on a bad ring index or options.
MapWorld BuildRingWorld(const map::Map& map, int ring, const MapWorldOptions& options,
                        std::mt19937_64& rng);

// Every ring of `map` in one world (rings share the building's coordinate frame).
MapWorld BuildMapWorld(const map::Map& map, const MapWorldOptions& options, std::mt19937_64& rng);

// A world position in map terms: the nearest edge of a built ring and how far along it.
struct MapPlace {
  MapEdgeRef ref;
  double offset_in = 0.0;    // from the edge's start node (ring order), scaled to metric_in
  double distance_in = 0.0;  // from the position to the edge's segment
};

// The built edge nearest `p_W_in` (within max_distance_in), for ground truth: e.g. the
// point where the optical axis meets the wall, or the robot position projected onto its
// hallway wall. Ties go to the first edge in ring order.
std::optional<MapPlace> LocateOnMap(
    const MapWorld& world, const Eigen::Vector2d& p_W_in,
    double max_distance_in = std::numeric_limits<double>::infinity());

}  // namespace stickrep::world
