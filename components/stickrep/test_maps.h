#pragma once

// Small hand-made maps shared by the map library's tests.

#include <algorithm>
#include <stdexcept>
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

// A corridor outline in format 2: a 96 in corridor 400 in long, walked with the wall on
// the right (counter-clockwise round the free space: every corner is a 270), with a measured 53 in double door, a 34 in door of class 32 and an opening of
// 90 in.
inline const std::string kCorridorMapYaml = R"(stickrep_map: 2
name: corridor
rings:
  - id: c
    closed: true
    outline: corridor
    width_in: 96
    path:
      - node: {angle_deg: 270, xyz_in: [96, 0, 0]}
      - edge: {type: hallway, metric_in: 100}
      - node: {angle_deg: 180, xyz_in: [96, 100, 0]}
      - edge: {type: doorway, width_in: 53}
      - node: {angle_deg: 180, xyz_in: [96, 153, 0]}
      - edge: {type: hallway, metric_in: 47}
      - node: {angle_deg: 180, xyz_in: [96, 200, 0]}
      - edge: {type: opening, metric_in: 90}
      - node: {angle_deg: 180, xyz_in: [96, 290, 0]}
      - edge: {type: hallway, metric_in: 110}
      - node: {angle_deg: 270, xyz_in: [96, 400, 0]}
      - edge: {type: hallway, metric_in: 96}
      - node: {angle_deg: 270, xyz_in: [0, 400, 0]}
      - edge: {type: hallway, metric_in: 166}
      - node: {angle_deg: 180, xyz_in: [0, 234, 0]}
      - edge: {type: doorway, class: "32", width_in: 34}
      - node: {angle_deg: 180, xyz_in: [0, 200, 0]}
      - edge: {type: hallway, metric_in: 200}
      - node: {angle_deg: 270, xyz_in: [0, 0, 0]}
      - edge: {type: hallway, metric_in: 96}
)";

// The box map with `from` replaced by `to`; throws (failing the test) when the map has no
// `from`, so a test never checks an edit that was not made.
inline std::string EditedBoxMap(const std::string& from, const std::string& to) {
  std::string text = kBoxMapYaml;
  const auto at = text.find(from);
  if (at == std::string::npos) throw std::invalid_argument("the box map has no '" + from + "'");
  return text.replace(at, from.size(), to);
}

// 1-based line of the first occurrence of `needle` in `text`.
inline int LineOf(const std::string& text, const std::string& needle) {
  const auto at = text.find(needle);
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + at, '\n'));
}

}  // namespace stickrep::map::testing
