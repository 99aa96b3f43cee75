#include "localizer/map_msg.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace stickrep::localizer {

namespace {

// EdgeType and the IDL's EdgeKind list the same kinds in the same order.
static_assert(static_cast<int>(msgs::EDGE_OPENING) == static_cast<int>(map::EdgeType::kOpening) &&
                  static_cast<int>(map::EdgeType::kOpening) + 1 == map::kEdgeTypeCount,
              "idl/localization.idl's EdgeKind and map::EdgeType differ");

map::EdgeType EdgeTypeOf(const msgs::MapEdge& e, const std::string& where) {
  const int kind = static_cast<int>(e.kind());
  if (kind < 0 || kind >= map::kEdgeTypeCount) {
    throw std::invalid_argument(where + ": unknown edge kind " + std::to_string(kind));
  }
  return static_cast<map::EdgeType>(kind);
}

map::Edge EdgeOf(const msgs::MapEdge& e, const std::string& where) {
  map::Edge edge;
  edge.type = EdgeTypeOf(e, where);
  edge.metric_in = e.metric_in();
  edge.prototype = map::DefaultPrototype(edge.type);
  edge.pattern = e.pattern();
  if (edge.IsDoor()) {
    edge.door_class = map::ParseDoorClass(e.door_class());
    if (!edge.door_class) {
      throw std::invalid_argument(where + ": a doorway with door class '" + e.door_class() + "'");
    }
  }
  return edge;
}

// The end node of an open ring (see FromMsg in the header).
map::Node EndNode(const map::Ring& ring) {
  const int last = ring.EdgeCount() - 1;
  const map::Node& start = ring.nodes[last];
  double heading = 0.0;
  if (last > 0) {
    const map::Node& before = ring.nodes[last - 1];
    heading = std::atan2(start.y_in - before.y_in, start.x_in - before.x_in) +
              (start.angle_deg - 180.0) * M_PI / 180.0;
  }
  map::Node end;
  end.x_in = start.x_in + ring.edges[last].metric_in * std::cos(heading);
  end.y_in = start.y_in + ring.edges[last].metric_in * std::sin(heading);
  return end;
}

}  // namespace

msgs::StickRepMap ToMsg(const map::Map& m) {
  msgs::StickRepMap out;
  out.name(m.info().name);
  for (const map::Ring& r : m.rings()) {
    msgs::MapRing ring;
    ring.ring_id(r.id);
    ring.closed(r.closed);
    for (int i = 0; i < r.EdgeCount(); ++i) {
      const map::Edge& e = r.edges[i];
      msgs::MapEdge edge;
      edge.kind(static_cast<msgs::EdgeKind>(static_cast<int>(e.type)));
      edge.metric_in(e.metric_in);
      edge.door_class(e.door_class ? map::DoorClassName(*e.door_class) : "");
      edge.pattern(e.pattern);
      edge.start_angle_deg(r.nodes[i].angle_deg);
      edge.x_in(r.nodes[i].x_in);
      edge.y_in(r.nodes[i].y_in);
      ring.edges().push_back(edge);
    }
    out.rings().push_back(ring);
  }
  return out;
}

map::Map FromMsg(const msgs::StickRepMap& msg) {
  std::vector<map::Ring> rings;
  for (const msgs::MapRing& r : msg.rings()) {
    map::Ring ring;
    ring.id = r.ring_id();
    ring.closed = r.closed();
    for (std::size_t i = 0; i < r.edges().size(); ++i) {
      const msgs::MapEdge& e = r.edges()[i];
      ring.edges.push_back(EdgeOf(e, "ring '" + r.ring_id() + "' edge " + std::to_string(i)));
      map::Node node;
      node.angle_deg = e.start_angle_deg();
      node.x_in = e.x_in();
      node.y_in = e.y_in();
      ring.nodes.push_back(node);
    }
    if (!ring.closed && !ring.edges.empty()) ring.nodes.push_back(EndNode(ring));
    rings.push_back(std::move(ring));
  }
  map::MapInfo info;
  info.name = msg.name();
  return map::Map(std::move(info), std::move(rings));
}

}  // namespace stickrep::localizer
