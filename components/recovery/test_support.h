#pragma once

// A small hand-made floor shared by the recovery tests: one closed ring along a corridor,
// doors of three classes, walls of distinct lengths, two convex corners.
//
//   0 W120  1 D36  2 W60  3 D36  4 W60  5 D32  6 W200  7 D40  8 W90  9 D36  10 W75
//   11 D40  12 W150        (node 0 and node 12 are 90° corners, the rest 180°)

#include <utility>
#include <vector>

#include "stickrep/map.h"
#include "stickrep/sequence_matcher.h"

namespace stickrep::recovery::testing {

// A closed ring "corridor" of `edges`, its nodes 90° corners at `corners` and 180° elsewhere,
// laid out along x by the edges' lengths.
inline map::Map ClosedCorridor(std::vector<map::Edge> edges, const std::vector<int>& corners) {
  map::Ring ring;
  ring.id = "corridor";
  ring.closed = true;
  ring.edges = std::move(edges);
  double x = 0;
  for (std::size_t i = 0; i < ring.edges.size(); ++i) {
    map::Node n;
    n.angle_deg = 180.0;
    for (const int c : corners) {
      if (static_cast<std::size_t>(c) == i) n.angle_deg = 90.0;
    }
    n.x_in = x;
    ring.nodes.push_back(n);
    x += ring.edges[i].metric_in;
  }
  map::MapInfo info;
  info.name = "corridor";
  return map::Map(info, {ring});
}

inline map::Map CorridorMap() {
  using map::DoorClass;
  using map::Edge;
  return ClosedCorridor(
      {Edge::Wall(120), Edge::Door(DoorClass::k36), Edge::Wall(60), Edge::Door(DoorClass::k36),
       Edge::Wall(60), Edge::Door(DoorClass::k32), Edge::Wall(200), Edge::Door(DoorClass::k40),
       Edge::Wall(90), Edge::Door(DoorClass::k36), Edge::Wall(75), Edge::Door(DoorClass::k40),
       Edge::Wall(150)},
      {0, 12});
}

inline map::SensedEdge Wall(double in, double angle = 180.0, bool lower_bound = false) {
  map::SensedEdge e;
  e.code = map::kWallCode;
  e.metric_in = in;
  e.angle_deg = angle;
  e.metric_is_lower_bound = lower_bound;
  return e;
}

inline map::SensedEdge Door(map::DoorClass c, double width_in = 0.0, double angle = 180.0) {
  map::SensedEdge e;
  e.code = map::DoorCode(c);
  e.metric_in = width_in > 0 ? width_in : map::DoorClassWidthIn(c);
  e.angle_deg = angle;
  return e;
}

}  // namespace stickrep::recovery::testing
