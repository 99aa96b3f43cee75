#pragma once

// Small hand-made maps shared by the map library's tests.

#include <string>

namespace stickrep::map::testing {

// A closed rectangle of 100 in x 100 in walked clockwise from its north-west corner (convex
// corners): wall 40, door 36, wall 24 along the north side, then three 100 in walls; and an
// open strip (wall 50, door 32) joined to it at the strip's artificial first node.
inline const std::string kBoxMapYaml = R"(stickrep_map: 1
name: box
description: "test map"
rings:
  - id: box
    closed: true
    path:
      - node: {angle_deg: 90, xyz_in: [0, 100, 0]}
      - edge: {type: hallway, metric_in: 40}
      - node: {angle_deg: 180, xyz_in: [40, 100, 0]}
      - edge: {type: doorway, class: "36", pattern: poster}
      - node: {angle_deg: 180, xyz_in: [76, 100, 0]}
      - edge: {type: hallway, metric_in: 24}
      - node: {angle_deg: 90, xyz_in: [100, 100, 0]}
      - edge: {type: hallway, metric_in: 100}
      - node: {angle_deg: 90, xyz_in: [100, 0, 0]}
      - edge: {type: hallway, metric_in: 100}
      - node: {angle_deg: 90, xyz_in: [0, 0, 0]}
      - edge: {type: hallway, metric_in: 100}
  - id: strip
    closed: false
    path:
      - node: {angle_deg: 180, xyz_in: [0, 200, 0], artificial: true}
      - edge: {type: hallway, metric_in: 50}
      - node: {angle_deg: 180, xyz_in: [50, 200, 0]}
      - edge: {type: doorway, class: "32"}
      - node: {angle_deg: 180, xyz_in: [82, 200, 0]}
joins:
  - {ring: strip, node: 0, to_ring: box, to_node: 0}
)";

}  // namespace stickrep::map::testing
