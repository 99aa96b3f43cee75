#pragma once

// What `stickrep-console pose` shows, kept apart from DDS: the map drawn as a character grid
// for a terminal with the robot's best pose as an arrow and the other hypotheses as digits,
// the pose as JSON, and the map to scale as a PNG with the same overlays.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "stickrep/map.h"

namespace stickrep::console {

// One place the robot may be, as the localizer reports it (msgs::PoseHypothesis): edge
// `edge` of ring `ring_id`, travelled in ring order when `forward`, `offset_in` into it; and
// the same place in the building frame (inches, heading counter-clockwise from +x).
struct PoseMark {
  std::string ring_id;
  int edge = 0;
  bool forward = true;
  double offset_in = 0.0;
  double x_in = 0.0;
  double y_in = 0.0;
  double heading_rad = 0.0;
  double probability = 0.0;
};

// One refresh of `pose`: the localizer's latest pose (localization/pose) and candidates
// (localization/hypotheses).
struct PoseFrame {
  std::string status;  // RECOVERING, LOCALIZED or LOST
  double confidence = 0.0;
  int candidates = 0;
  int edges_sensed = 0;
  std::string message;
  std::optional<PoseMark> best;      // none until the localizer has a hypothesis
  std::vector<PoseMark> hypotheses;  // best first
  double age_s = 0.0;                // since the localizer wrote the pose
};

// At most this many other hypotheses are drawn, as the digits 1..9.
inline constexpr int kMaxDrawnHypotheses = 9;

// The hypotheses other than the best (another ring, edge or direction), best ranked first;
// the first of them is drawn as '1'.
std::vector<PoseMark> OtherHypotheses(const PoseFrame& frame);

// '>', '^', '<' or 'v': the arrow nearest a heading (east, north, west, south on the map).
char HeadingArrow(double heading_rad);

// The map rasterised into characters, north up. A terminal cell is about twice as tall as
// it is wide, so a cell covers cell_in across and 2 * cell_in up the map.
struct CharGrid {
  std::vector<std::string> rows;
  double min_x_in = 0.0;
  double max_y_in = 0.0;
  double cell_in = 1.0;

  int cols() const { return rows.empty() ? 0 : static_cast<int>(rows.front().size()); }
  // (row, column) of the cell holding a building-frame point; may lie off the grid.
  std::pair<int, int> CellOf(double x_in, double y_in) const;
  bool Contains(std::pair<int, int> cell) const;
};

// The map `cols` characters wide (at least 2): walls as '-', '|', '/' or '\' along their
// direction, doors '+', elevators 'E', stairwells 'S', other edges '.'; then the other
// hypotheses as digits by rank and the best pose as its HeadingArrow on top.
CharGrid DrawPoseGrid(const map::Map& map, const PoseFrame& frame, int cols);

// "LOCALIZED  confidence 0.97  candidates 1  edges sensed 23  best wing1_corridor/17 forward
// +12.0 in (x 1234.0, y 56.0 in, heading 90 deg)  pose age 0.4 s" on one line.
std::string PoseHeader(const PoseFrame& frame);

// The header, the grid and a legend line with the scale: one terminal frame.
std::string RenderPoseText(const map::Map& map, const PoseFrame& frame, int cols);

// {"status", "confidence", "candidates", "edges_sensed", "age_s", "message", "best" (null
// when none), "hypotheses": [...]}, each pose with ring, edge, forward, offset_in, x_in,
// y_in, heading_rad and probability.
nlohmann::json PoseJson(const PoseFrame& frame);

// The map to scale (map_render.h) with the best pose as a labelled arrow and the other
// hypotheses as dots with arrows labelled by rank. Throws std::runtime_error when the file
// cannot be written.
void WritePosePng(const map::Map& map, const PoseFrame& frame, const std::string& path);

}  // namespace stickrep::console
