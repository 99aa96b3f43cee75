#pragma once

// Starting-location ambiguity (§6.2, Figure 6.1; §6.4.1): for every start and direction of
// travel, how many edges the robot must sense, with no sensing error, before the sensed
// sequence matches one place only. Semantics (docs/maps.md): the start indexes a whole map
// edge (Figure 6.2 step 1), every edge from there on is sensed exactly — door class, wall
// metric, adjacency angle at each node crossed — and matched against both directions of
// every ring.

#include <vector>

#include "stickrep/map.h"
#include "stickrep/sequence_matcher.h"

namespace stickrep::map {

struct AmbiguityOptions {
  MatchTolerance tolerance;  // all zero: exact matching (no sensing error)
  // Compare adjacency angles (sonar-sensed corners). Off: types and metrics only.
  bool use_angles = true;
  // The robot starts at a random point inside its first edge (Figure 6.2 steps 0-1). A door
  // there is seen whole, but a wall only from the start point on, and only complete features
  // are matched (§6.4.1), so a first wall matches any wall. Off: the first edge is sensed
  // whole, as if every start were at a node.
  bool partial_first_edge = true;
};

// How one start ended.
enum class StartOutcome {
  kUnique,       // one candidate left: the true place
  kRingEnd,      // an open ring ended first
  kNeverUnique,  // still ambiguous after so many edges that it can never become unique
};

struct StartResult {
  Cursor start;
  StartOutcome outcome = StartOutcome::kUnique;
  int edges = 0;           // edges sensed when the outcome was reached
  int candidates = 0;      // candidates left then (1 for kUnique)
  double distance_in = 0;  // summed metric of the sensed edges
  double first_metric_in = 0;
};

struct AmbiguityResult {
  std::vector<StartResult> starts;  // ring by ring, edge by edge, dir +1 then -1
  int unique = 0;
  int ring_end = 0;
  int never_unique = 0;
  // Over the starts that became unique:
  double mean_edges = 0;                  // each start counted once (Figure 6.1)
  double length_weighted_mean_edges = 0;  // starts weighted by their first edge's length
  double mean_distance_in = 0;            // summed metric of the sensed edges
  int max_edges = 0;
  double mean_edge_metric_in = 0;  // of the map, for the paper's distance = edges * mean
};

AmbiguityResult AnalyseAmbiguity(const Map& map, const AmbiguityOptions& options = {});

}  // namespace stickrep::map
