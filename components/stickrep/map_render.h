#pragma once

// Draws a map to scale as a PNG: every ring's walls as thin lines, doors as thick lines
// coloured by class, artificial nodes and joins marked, with a legend. OpenCV lives here and
// in no part of the map library itself.

#include <string>

#include "stickrep/map.h"

namespace stickrep::map {

struct RenderOptions {
  int width_px = 1800;  // image width; the height follows the map's aspect ratio
  bool label_rings = true;
};

// Throws std::runtime_error if the file cannot be written.
void RenderMapPng(const Map& map, const std::string& path, const RenderOptions& options = {});

}  // namespace stickrep::map
