#include "stickrep/map.h"

#include <cassert>
#include <cmath>
#include <set>
#include <stdexcept>

namespace stickrep::map {

namespace {

constexpr const char* kEdgeTypeNames[] = {"corner",  "doorway", "elevator", "hallway",
                                          "pattern", "stairwell", "opening"};
constexpr const char* kPrototypeNames[] = {"doorjam", "wallsegment", "pattern"};
constexpr const char* kDoorClassNames[] = {"30", "32", "36", "40", "30/30", "36/36"};
constexpr double kDoorClassWidthsIn[] = {30.0, 32.0, 36.0, 40.0, 60.0, 72.0};

[[noreturn]] void Invalid(const std::string& what) { throw std::invalid_argument(what); }

}  // namespace

const char* EdgeTypeName(EdgeType type) { return kEdgeTypeNames[static_cast<int>(type)]; }

std::optional<EdgeType> ParseEdgeType(std::string_view name) {
  for (int i = 0; i < kEdgeTypeCount; ++i) {
    if (name == kEdgeTypeNames[i]) return static_cast<EdgeType>(i);
  }
  return std::nullopt;
}

const char* PrototypeName(Prototype prototype) {
  return kPrototypeNames[static_cast<int>(prototype)];
}

std::optional<Prototype> ParsePrototype(std::string_view name) {
  for (int i = 0; i < 3; ++i) {
    if (name == kPrototypeNames[i]) return static_cast<Prototype>(i);
  }
  return std::nullopt;
}

Prototype DefaultPrototype(EdgeType type) {
  switch (type) {
    case EdgeType::kDoorway:
      return Prototype::kDoorjam;
    case EdgeType::kPattern:
      return Prototype::kPattern;
    default:
      return Prototype::kWallsegment;
  }
}

const char* DoorMarkName(DoorMark mark) {
  switch (mark) {
    case DoorMark::kUnknown: return "unknown";
    case DoorMark::kPlain: return "plain";
    case DoorMark::kWindow: return "window";
    case DoorMark::kPoster: return "poster";
  }
  return "unknown";
}

std::optional<DoorMark> ParseDoorMark(std::string_view name) {
  for (int k = 0; k < kDoorMarkCount; ++k) {
    const auto mark = static_cast<DoorMark>(k);
    if (name == DoorMarkName(mark)) return mark;
  }
  return std::nullopt;
}

DoorMark DoorMarkOfPattern(std::string_view pattern) {
  if (pattern.find("poster") != std::string_view::npos) return DoorMark::kPoster;
  if (pattern.find("window") != std::string_view::npos && pattern.rfind("no_", 0) != 0) {
    return DoorMark::kWindow;
  }
  if (pattern == "plain" || pattern.rfind("no_", 0) == 0) return DoorMark::kPlain;
  return DoorMark::kUnknown;
}

const char* DoorClassName(DoorClass door_class) {
  return kDoorClassNames[static_cast<int>(door_class)];
}

std::optional<DoorClass> ParseDoorClass(std::string_view name) {
  for (int i = 0; i < kDoorClassCount; ++i) {
    if (name == kDoorClassNames[i]) return static_cast<DoorClass>(i);
  }
  return std::nullopt;
}

double DoorClassWidthIn(DoorClass door_class) {
  return kDoorClassWidthsIn[static_cast<int>(door_class)];
}

std::optional<DoorClass> NearestDoorClass(double width_in) {
  std::optional<DoorClass> best;
  double best_gap = kDoorClassToleranceIn;
  for (int i = 0; i < kDoorClassCount; ++i) {
    const double gap = std::abs(width_in - kDoorClassWidthsIn[i]);
    if (gap <= best_gap) {
      best_gap = gap;
      best = static_cast<DoorClass>(i);
    }
  }
  return best;
}

const char* OutlineName(Outline outline) {
  return outline == Outline::kCorridor ? "corridor" : "side";
}

bool IsDoubleDoor(DoorClass door_class) {
  return door_class == DoorClass::k30_30 || door_class == DoorClass::k36_36;
}

DoorClass LeafClass(DoorClass door_class) {
  if (door_class == DoorClass::k30_30) return DoorClass::k30;
  if (door_class == DoorClass::k36_36) return DoorClass::k36;
  return door_class;
}

bool IsOpenEnd(const Edge& edge, double angle_before_deg, double angle_after_deg) {
  const double a = angle_before_deg - 180.0, b = angle_after_deg - 180.0;
  return edge.IsOpening() && std::abs(a) >= kOpenEndMinTurnDeg &&
         std::abs(b) >= kOpenEndMinTurnDeg && a * b > 0.0;
}

namespace {

// The edge `d` steps from edge `k` (around a closed ring), or -1 past an open ring's end.
int EdgeFrom(const Ring& ring, int k, int d) {
  const int n = ring.EdgeCount();
  int i = k + d;
  if (ring.closed) i = ((i % n) + n) % n;
  return i >= 0 && i < n ? i : -1;
}

bool IsDoorAt(const Ring& ring, int i) { return i >= 0 && ring.edges[i].door_class.has_value(); }

bool ShortWallBetweenDoors(const Ring& ring, int k) {
  const Edge& e = ring.edges[k];
  if (!e.IsWall() || e.metric_in >= kRowWallIn) return false;
  return IsDoorAt(ring, EdgeFrom(ring, k, -1)) && IsDoorAt(ring, EdgeFrom(ring, k, +1));
}

}  // namespace

bool InDoorRow(const Ring& ring, int k) {
  if (!IsDoorAt(ring, k)) return ShortWallBetweenDoors(ring, k);
  for (const int side : {-1, +1}) {
    const int next = EdgeFrom(ring, k, side);
    if (next < 0) continue;
    if (IsDoorAt(ring, next) || ShortWallBetweenDoors(ring, next)) return true;
  }
  return false;
}

Edge Edge::Wall(double metric_in) {
  Edge e;
  e.type = EdgeType::kHallway;
  e.metric_in = metric_in;
  e.prototype = Prototype::kWallsegment;
  return e;
}

Edge Edge::Door(DoorClass door_class, std::string pattern) {
  Edge e;
  e.type = EdgeType::kDoorway;
  e.metric_in = DoorClassWidthIn(door_class);
  e.prototype = Prototype::kDoorjam;
  e.door_class = door_class;
  e.pattern = std::move(pattern);
  return e;
}

Map::Map(MapInfo info, std::vector<Ring> rings, std::vector<Join> joins,
         std::vector<Obstacle> obstacles)
    : info_(std::move(info)),
      rings_(std::move(rings)),
      joins_(std::move(joins)),
      obstacles_(std::move(obstacles)) {
  for (const Obstacle& o : obstacles_) {
    if (o.id.empty()) Invalid("an obstacle has an empty id");
    if (o.polygon_in.size() < 3) Invalid("obstacle '" + o.id + "' has fewer than 3 corners");
    for (const auto& p : o.polygon_in) {
      if (!std::isfinite(p[0]) || !std::isfinite(p[1])) {
        Invalid("obstacle '" + o.id + "' has a corner that is not a finite number");
      }
    }
  }
  if (rings_.empty()) Invalid("a map needs at least one ring");
  std::set<std::string> ids;
  for (const Ring& ring : rings_) {
    const std::string where = "ring '" + ring.id + "'";
    if (ring.id.empty()) Invalid("a ring has an empty id");
    if (!ids.insert(ring.id).second) Invalid("ring id '" + ring.id + "' is used twice");
    if (ring.edges.empty()) Invalid(where + " has no edges");
    const std::size_t want = ring.edges.size() + (ring.closed ? 0 : 1);
    if (ring.nodes.size() != want) {
      Invalid(where + " has " + std::to_string(ring.nodes.size()) + " nodes; a " +
              (ring.closed ? "closed" : "open") + " ring of " + std::to_string(ring.edges.size()) +
              " edges needs " + std::to_string(want));
    }
    for (const Edge& e : ring.edges) {
      if (!(e.metric_in > 0.0) || !std::isfinite(e.metric_in)) {
        Invalid(where + " has an edge with metric " + std::to_string(e.metric_in) +
                " in; metrics must be > 0");
      }
      if (e.IsDoor() != e.door_class.has_value()) {
        Invalid(where + ": doorway edges, and only they, carry a door class");
      }
      if (e.IsDoor() &&
          std::abs(e.metric_in - DoorClassWidthIn(*e.door_class)) > kDoorClassToleranceIn) {
        Invalid(where + ": a door of class " + DoorClassName(*e.door_class) + " has metric " +
                std::to_string(e.metric_in) + " in");
      }
    }
    if (ring.width_in && !(*ring.width_in > 0.0 && std::isfinite(*ring.width_in))) {
      Invalid(where + " has a hallway width that is not > 0");
    }
    if (ring.outline == Outline::kCorridor && !ring.closed) {
      Invalid(where + ": a corridor outline is a closed ring");
    }
    for (const Node& n : ring.nodes) {
      if (!(n.angle_deg >= 0.0 && n.angle_deg <= 360.0)) {
        Invalid(where + " has a node angle outside [0, 360] deg");
      }
    }
    edge_count_ += ring.EdgeCount();
  }
  for (const Join& j : joins_) {
    const int a = FindRing(j.ring);
    const int b = FindRing(j.to_ring);
    if (a < 0) Invalid("a join names ring '" + j.ring + "', which does not exist");
    if (b < 0) Invalid("a join names ring '" + j.to_ring + "', which does not exist");
    if (a == b) Invalid("ring '" + j.ring + "' is joined to itself");
    if (j.node < 0 || j.node >= rings_[a].NodeCount()) {
      Invalid("a join names node " + std::to_string(j.node) + " of ring '" + j.ring + "'");
    }
    if (j.to_node < 0 || j.to_node >= rings_[b].NodeCount()) {
      Invalid("a join names node " + std::to_string(j.to_node) + " of ring '" + j.to_ring + "'");
    }
    if (!rings_[a].nodes[j.node].artificial) {
      Invalid("ring '" + j.ring + "' is joined at node " + std::to_string(j.node) +
              ", which is not marked artificial");
    }
  }
}

int Map::FindRing(std::string_view id) const {
  for (int r = 0; r < RingCount(); ++r) {
    if (rings_[r].id == id) return r;
  }
  return -1;
}

int Map::Wrap(int r, int i) const {
  const Ring& ring = rings_[r];
  const int n = ring.EdgeCount();
  if (ring.closed) {
    const int m = i % n;
    return m < 0 ? m + n : m;
  }
  return (i >= 0 && i < n) ? i : -1;
}

const Edge& Map::EdgeAt(int r, int i) const {
  const int w = Wrap(r, i);
  assert(w >= 0 && "EdgeAt: index off the end of an open ring");
  return rings_[r].edges[w];
}

bool Map::Advance(Cursor& c) const {
  const Ring& ring = rings_[c.ring];
  int next = c.edge + c.dir;
  if (ring.closed) {
    if (next == ring.EdgeCount()) next = 0;
    if (next < 0) next = ring.EdgeCount() - 1;
  } else if (next < 0 || next >= ring.EdgeCount()) {
    return false;
  }
  c.edge = next;
  return true;
}

const Node& Map::NodeAhead(const Cursor& c) const {
  const Ring& ring = rings_[c.ring];
  if (c.dir < 0) return ring.nodes[c.edge];
  const int n = c.edge + 1;
  return ring.nodes[ring.closed && n == ring.EdgeCount() ? 0 : n];
}

const Node& Map::NodeBehind(const Cursor& c) const {
  const Ring& ring = rings_[c.ring];
  if (c.dir > 0) return ring.nodes[c.edge];
  const int n = c.edge + 1;
  return ring.nodes[ring.closed && n == ring.EdgeCount() ? 0 : n];
}

}  // namespace stickrep::map
