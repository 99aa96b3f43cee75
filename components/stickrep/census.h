#pragma once

// The domain census of §6.2 (Tables 6.1–6.9) for any map. The text's tables have door30 but
// no 30/30 column, and their door-door pairs (11 door30-door30, 28 door36-door36) are the
// leaves of double doors; so the census counts a double door as its two leaves joined at a
// 180° node, and counts ordered pairs in ring order at every node that is not artificial
// (an artificial node is where a ring is joined to another, not a physical adjacency).

#include <array>

#include "stickrep/map.h"

namespace stickrep::map {

// Rows and columns of the census tables.
enum CensusClass { kCensusDoor30 = 0, kCensusDoor32, kCensusDoor36, kCensusDoor40, kCensusWall };

struct Census {
  // Tables 6.1–6.3: [angle 90/180/270][first][second].
  std::array<std::array<std::array<int, 5>, 5>, 3> pairs{};
  std::array<std::array<int, 4>, 4> door_wall_door{};       // Table 6.4
  std::array<int, 4> wall_door_wall{};                      // Table 6.5
  std::array<std::array<int, 4>, 4> door_wall_door_wall{};  // Table 6.6
  std::array<std::array<int, 4>, 4>
      wall_door_wall_door{};                        // Table 6.7 (180°, see paper_reference.h)
  std::array<std::array<int, 6>, 4> door_census{};  // Table 6.8 (blank = all doors)
  std::array<int, 11> wall_census{};                // Table 6.9

  int rings = 0;
  int closed_rings = 0;
  int joins = 0;
  int artificial_nodes = 0;
  int edges = 0;       // map edges (a double door is one edge)
  int leaf_edges = 0;  // with double doors counted as two leaves, as the text counts
  int walls = 0;
  int other_edges = 0;  // elevators, stairwells, corners, patterns: in no table
  std::array<int, kDoorClassCount> doors_by_class{};  // map edges
  int door_leaves = 0;
  int pairs_counted = 0;     // in Tables 6.1–6.3
  int pairs_other = 0;       // at non-artificial nodes but with another edge type or angle
  int pairs_artificial = 0;  // across artificial nodes, not counted
  double total_metric_in = 0;
  double mean_edge_metric_in = 0;  // per map edge
  double mean_leaf_metric_in = 0;  // per leaf edge (the text's 67.64 in basis)
};

Census ComputeCensus(const Map& map);

// Index 0/1/2 for an angle near 90/180/270 (within 45°), -1 otherwise.
int AngleBucket(double angle_deg);

}  // namespace stickrep::map
