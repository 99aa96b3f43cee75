#pragma once

#include <optional>
#include <string>
#include <vector>

#include "stickrep/map.h"

namespace stickrep::localizer {

// A map of one closed ring whose edges lie in a straight line along +x, for tests that
// only care about the edge sequence; `width_in` is the ring's hallway width, if given.
inline map::Map StraightRingMap(const std::vector<map::Edge>& edges, const std::string& name,
                                std::optional<double> width_in = std::nullopt) {
  map::Ring ring;
  ring.id = "hall";
  ring.width_in = width_in;
  ring.edges = edges;
  ring.nodes.resize(edges.size());
  double x = 0.0;
  for (std::size_t i = 0; i < edges.size(); ++i) {
    ring.nodes[i].x_in = x;
    x += edges[i].metric_in;
  }
  return map::Map(map::MapInfo{name, "", "", std::nullopt}, {ring});
}

}  // namespace stickrep::localizer
