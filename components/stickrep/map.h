#pragma once

// The StickRep map model (§3.3, §6.1): a building floor as rings of attributed edges (the
// walls and doors along one side of a hallway, in order) whose nodes carry the adjacency
// angle and global coordinates; rings are joined to other rings at artificial nodes.
// Standard library only: the simulation study and the localizer link this without DDS or
// OpenCV.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace stickrep::map {

// Edge types of §6.1. `kHallway` is the wall segment type ("hallway" in the text).
// `kOpening` (map format 2) is a gap in the wall the robot passes: a wide opening into a
// hall, a passage into a side corridor; neither a door nor a wall.
enum class EdgeType : std::uint8_t {
  kCorner,
  kDoorway,
  kElevator,
  kHallway,
  kPattern,
  kStairwell,
  kOpening
};
inline constexpr int kEdgeTypeCount = 7;

// Edge prototypes of §3.3 / §6.1.
enum class Prototype : std::uint8_t { kDoorjam, kWallsegment, kPattern };

// The legal door widths (§4.1.2, Table 4.1, Tables 6.1–6.8): singles and double doors.
enum class DoorClass : std::uint8_t { k30, k32, k36, k40, k30_30, k36_36 };
inline constexpr int kDoorClassCount = 6;

const char* EdgeTypeName(EdgeType type);
std::optional<EdgeType> ParseEdgeType(std::string_view name);
const char* PrototypeName(Prototype prototype);
std::optional<Prototype> ParsePrototype(std::string_view name);
// The prototype an edge of `type` has when the file does not say (doorway -> doorjam,
// pattern -> pattern, everything else -> wallsegment).
Prototype DefaultPrototype(EdgeType type);

// "30", "32", "36", "40", "30/30", "36/36".
const char* DoorClassName(DoorClass door_class);
std::optional<DoorClass> ParseDoorClass(std::string_view name);
// Nominal ribbon width in inches: 30, 32, 36, 40, 60, 72.
double DoorClassWidthIn(DoorClass door_class);
bool IsDoubleDoor(DoorClass door_class);
// A measured door opening may differ from its class width by at most this much (map format
// 2 keeps the measured width; real openings of 51-55 in are 60 in doubles, §4.1.2 lists the
// classes only). Wider gaps are `opening` edges.
inline constexpr double kDoorClassToleranceIn = 12.0;
// The class whose width is nearest `width_in`, if it lies within kDoorClassToleranceIn.
std::optional<DoorClass> NearestDoorClass(double width_in);
// The class of one leaf of a door: 30/30 -> 30, 36/36 -> 36, singles -> themselves.
DoorClass LeafClass(DoorClass door_class);

// What the camera can tell of a door's leaf: the supplemental marks of Table 6.8 reduced
// to what a frame shows (a glazed vision panel, a poster, or a plain leaf). kUnknown: the
// leaf was not read (nothing in view, too little contrast), or on a map door, not surveyed.
enum class DoorMark : std::uint8_t { kUnknown, kPlain, kWindow, kPoster };
inline constexpr int kDoorMarkCount = 4;
// "unknown", "plain", "window", "poster".
const char* DoorMarkName(DoorMark mark);
std::optional<DoorMark> ParseDoorMark(std::string_view name);
// The mark a map `pattern` puts on a door: a pattern naming a poster is a poster, one naming
// a window (but not "no_window") a window, "plain" or one beginning "no_" a plain leaf. Any
// other pattern, and none, is kUnknown: the survey did not say what the leaf shows (a floor
// plan drawn from an architect's drawing lists no marks), so a read there says nothing.
DoorMark DoorMarkOfPattern(std::string_view pattern);

// One attributed edge (§6.1). Doors carry their class and a metric: the class width (map
// format 1) or the measured width of the opening (format 2), within kDoorClassToleranceIn
// of the class width.
struct Edge {
  EdgeType type = EdgeType::kHallway;
  double metric_in = 0.0;  // length (walls) or width (doors, elevators), > 0
  Prototype prototype = Prototype::kWallsegment;
  std::optional<DoorClass> door_class;  // set exactly for doorways
  std::string pattern;                  // supplemental marks (Table 6.8); empty if none

  bool IsDoor() const { return type == EdgeType::kDoorway; }
  bool IsWall() const { return type == EdgeType::kHallway; }
  bool IsOpening() const { return type == EdgeType::kOpening; }

  static Edge Wall(double metric_in);
  static Edge Door(DoorClass door_class, std::string pattern = "");
};

// A corridor's open end (map format 2): an opening between two corners that turn the same
// way by at least kOpenEndMinTurnDeg (a corridor outline runs up one side, across the gap
// and back down the other). A robot following the corridor passes out through it into
// space the ring does not describe, where an opening between coplanar walls (a side
// opening) it passes along the wall. `angle_before` and `angle_after` are the nodes at the
// edge's ends.
inline constexpr double kOpenEndMinTurnDeg = 45.0;
bool IsOpenEnd(const Edge& edge, double angle_before_deg, double angle_after_deg);

// One node: the adjacency angle between its two incident edges, measured inside the solid
// (90 convex corner, 180 coplanar, 270 concave corner: §3.3), and its global pose.
struct Node {
  double angle_deg = 180.0;
  double x_in = 0.0;
  double y_in = 0.0;
  double z_in = 0.0;
  double alpha_deg = 0.0;
  double beta_deg = 0.0;
  double gamma_deg = 0.0;   // heading of the wall leaving this node, in ring order
  bool artificial = false;  // the node where this ring is joined to another ring (§3.3)
};

// Doors in a row (the hallway's look changes most from door to door there: panels and
// pilasters between them, dark leaves, double doors read leaf by leaf). A wall shorter than
// kRowWallIn between two doors joins them into a row; a door is in a row when another door
// is beside it or across such a wall. The landmark pipeline's error rates are measured and
// modelled apart for doors in a row and doors alone, and for those short walls and the rest
// (recovery::ErrorModel::in_row).
inline constexpr double kRowWallIn = 60.0;
struct Ring;
// Whether edge `k` of `ring` is a door in a row, or a wall under kRowWallIn between two
// doors: the edges the error model gives its in-row rates.
bool InDoorRow(const Ring& ring, int k);

// What a ring outlines (map format 2). A `kSide` ring is one side of a hallway (the rings
// of §3.3): the hallway's other side is another ring, or, for a ring simulated on its own,
// a wall the simulation adds. A `kCorridor` ring is the closed outline of a corridor's free
// space, both sides and its ends: nothing is added opposite it.
enum class Outline : std::uint8_t { kSide, kCorridor };
const char* OutlineName(Outline outline);

// One ring: the edges along one side of a hallway in order, walking with the wall on the
// right. Node i is the node at the start of edge i. A closed ring has as many nodes as
// edges (node 0 closes the ring); an open ring has one node more (its two ends).
struct Ring {
  std::string id;
  bool closed = true;
  Outline outline = Outline::kSide;
  // Width of the hallway along this ring (map format 2), when the map gives it: the
  // distance to the opposite wall of a side ring, the corridor's usual width for a
  // corridor outline (where the follower's axis runs).
  std::optional<double> width_in;
  std::vector<Edge> edges;
  std::vector<Node> nodes;

  int EdgeCount() const { return static_cast<int>(edges.size()); }
  int NodeCount() const { return static_cast<int>(nodes.size()); }
  // The sum of the edges' metrics: the ring's length along its walls.
  double LengthIn() const {
    double sum = 0.0;
    for (const Edge& e : edges) sum += e.metric_in;
    return sum;
  }
};

// Ring `ring` is joined at its artificial node `node` to node `to_node` of ring `to_ring`.
struct Join {
  std::string ring;
  int node = 0;
  std::string to_ring;
  int to_node = 0;
};

// A solid the robot passes but never follows (map format 2): a free-standing column, a
// pier, a display case. The world builds it; the localizer does not match it. Its outline
// is a closed polygon in the building frame (at least 3 corners, any orientation).
struct Obstacle {
  std::string id;
  std::vector<std::array<double, 2>> polygon_in;
};

// Where a map came from: free text plus, for generated maps, the generator and its seed.
struct MapInfo {
  std::string name;
  std::string description;
  std::string generator;  // e.g. "stickrep-map generate engineering_building_3f"
  std::optional<std::uint64_t> seed;
};

// A position on the map with a direction of travel: edge `edge` of ring `ring`, travelled
// in ring order (dir = +1) or against it (dir = -1).
struct Cursor {
  int ring = 0;
  int edge = 0;
  int dir = +1;
  bool operator==(const Cursor& o) const {
    return ring == o.ring && edge == o.edge && dir == o.dir;
  }
};

// A whole floor. Immutable after construction; the constructor checks the structure (node
// counts, door classes, metrics, angles, unique ids, joins) and throws
// std::invalid_argument with a plain message. Files are checked with line numbers by the
// loader (map_io.h) before they get here.
class Map {
 public:
  Map() = default;
  Map(MapInfo info, std::vector<Ring> rings, std::vector<Join> joins = {},
      std::vector<Obstacle> obstacles = {});

  const MapInfo& info() const { return info_; }
  const std::vector<Ring>& rings() const { return rings_; }
  const std::vector<Join>& joins() const { return joins_; }
  const std::vector<Obstacle>& obstacles() const { return obstacles_; }
  int RingCount() const { return static_cast<int>(rings_.size()); }
  const Ring& ring(int r) const { return rings_[r]; }
  // Index of the ring called `id`, or -1.
  int FindRing(std::string_view id) const;
  // Total number of edges over all rings.
  int EdgeCount() const { return edge_count_; }

  // Edge i of ring r; wraps around closed rings (any i), open rings need 0 <= i < size.
  const Edge& EdgeAt(int r, int i) const;
  // Index of edge i wrapped into [0, size) for a closed ring; -1 off the end of an open one.
  int Wrap(int r, int i) const;
  // Moves the cursor one edge along its direction; false (cursor unchanged) at the end of an
  // open ring.
  bool Advance(Cursor& c) const;
  // The node the cursor crosses when it advances: the end of its edge in travel direction.
  const Node& NodeAhead(const Cursor& c) const;
  // The node behind the cursor: the start of its edge in travel direction.
  const Node& NodeBehind(const Cursor& c) const;

 private:
  MapInfo info_;
  std::vector<Ring> rings_;
  std::vector<Join> joins_;
  std::vector<Obstacle> obstacles_;
  int edge_count_ = 0;
};

}  // namespace stickrep::map
