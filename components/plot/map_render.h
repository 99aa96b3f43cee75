#pragma once

// Draws a map to scale as a PNG: every ring's walls as thin lines, doors as thick lines
// coloured by class, artificial nodes and joins marked, with a legend. OpenCV lives here and
// in no part of the map library itself.

#include <string>
#include <utility>
#include <vector>

#include "stickrep/map.h"

namespace stickrep::map {

// Something drawn over the map in building coordinates (inches): a robot's path, or a
// marked moment such as the start or the recovery of the pose.
struct PathOverlay {
  std::vector<std::pair<double, double>> points_in;  // (x, y)
};
struct MarkerOverlay {
  double x_in = 0.0;
  double y_in = 0.0;
  std::string label;
};
// A pose of the robot: a labelled dot with an arrow along its heading (building frame:
// radians counter-clockwise from +x).
struct PoseOverlay {
  double x_in = 0.0;
  double y_in = 0.0;
  double heading_rad = 0.0;
  std::string label;
};

struct RenderOptions {
  int width_px = 1800;  // image width; the height follows the map's aspect ratio
  bool label_rings = true;
  std::vector<PathOverlay> paths;      // drawn in red
  std::vector<MarkerOverlay> markers;  // drawn as labelled dots
  std::vector<PoseOverlay> poses;      // drawn as labelled dots with arrows, in order
};

// Throws std::runtime_error if the file cannot be written.
void RenderMapPng(const Map& map, const std::string& path, const RenderOptions& options = {});

}  // namespace stickrep::map
