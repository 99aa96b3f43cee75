#pragma once

// Route planning for the mission executive: from the localized pose to a goal named on
// `mission/goal`, along the rings of the StickRep map (§3.3: the robot travels a "feature
// highway" of edges, crossing between rings at their artificial join nodes). Standard
// library and the map only: the executive node turns the plan into motion commands.
//
// Goal names (what `mission/goal` carries):
//   "RING/EDGE"        edge EDGE (0-based, ring order) of the ring with id RING; the goal is
//                      the edge's midpoint, where a door is centred in the camera's view.
//                      Example: "wing1_corridor/74".
//   "RING/node/NODE"   node NODE of ring RING (node i starts edge i; an open ring's last
//                      node is its far end). Example: "core/node/0".
//   "pattern:NAME"     the one edge whose `pattern` is NAME (maps/README.md: old_window,
//                      poster, artificial_ribbon, ...). The shipped maps carry no door
//                      numbers; a pattern names a door only where exactly one edge has it
//                      (e.g. "pattern:artificial_ribbon" in wells_hall_7f_modified), so a
//                      pattern on several edges is rejected as ambiguous.
// Ring ids are one word of letters, digits, '_', '-', '.' (maps/README.md), so '/' and ':'
// cannot be part of one. Whitespace around the name is ignored.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stickrep/map.h"

namespace stickrep::executive {

// Where the robot is on the map: inside edge `edge` of ring `ring`, travelling in ring order
// (dir = +1) or against it (dir = -1), offset_in past the edge's start in the travel
// direction (the localizer's pose: localizer::Hypothesis ring, edge, dir, offset_in).
struct MapPose {
  int ring = 0;
  int edge = 0;
  int dir = +1;
  double offset_in = 0.0;
};

enum class GoalKind { kEdge, kNode };

// A parsed goal: edge or node `index` of ring `ring`.
struct Goal {
  GoalKind kind = GoalKind::kEdge;
  int ring = 0;
  int index = 0;
  std::string name;  // as given, trimmed
};

// A goal, or why the name does not denote one.
struct GoalResult {
  std::optional<Goal> goal;
  std::string error;
  explicit operator bool() const { return goal.has_value(); }
};

// One stretch of travel along one ring.
struct RouteLeg {
  int ring = 0;
  int dir = +1;              // +1: ring order, -1: against it
  double distance_in = 0.0;  // along the edges
  // The node where the leg ends (a join node to cross, or a node goal); -1 when the leg ends
  // inside an edge (an edge goal).
  int end_node = -1;
};

// Crossing from one ring to another at a join (the hallway between the two artificial
// nodes): from node `from_node` of ring `from_ring` to node `to_node` of ring `to_ring`.
struct JoinCrossing {
  int from_ring = 0;
  int from_node = 0;
  int to_ring = 0;
  int to_node = 0;
  double distance_in = 0.0;  // straight line between the two nodes' coordinates
};

// The plan: legs in order, a join crossing between consecutive legs.
struct Route {
  Goal goal;
  double distance_in = 0.0;  // total: legs plus crossings
  std::vector<RouteLeg> legs;
  std::vector<JoinCrossing> crossings;
  // +1: keep the current direction of travel; -1: reverse it first (the goal is the other
  // way round, or behind); 0: already at the goal.
  int initial_travel_sign = 0;
};

// A route, or why there is none (bad pose, bad goal, goal not reachable).
struct RouteResult {
  std::optional<Route> route;
  std::string error;
  explicit operator bool() const { return route.has_value(); }
};

// Plans shortest routes on one map. The rings are a graph: consecutive nodes of a ring are
// linked by their edge (cost: its metric), a closed ring also from its last node back to
// node 0, and each join links its two artificial nodes (cost: the straight-line distance
// between their coordinates, the walk across the hallway). Dijkstra from the pose to the
// goal; on a closed ring this picks the shorter way round. Holds a reference to `map`,
// which must outlive it. Plan() and ParseGoal() never throw; errors come back as values.
class RoutePlanner {
 public:
  explicit RoutePlanner(const map::Map& map);

  GoalResult ParseGoal(std::string_view name) const;
  RouteResult Plan(const MapPose& pose, const Goal& goal) const;
  RouteResult Plan(const MapPose& pose, std::string_view goal_name) const;

  // One line for `mission/status`: "goal 'box/1': 42.0 in; ring box in ring order 42.0 in".
  std::string Describe(const Route& route) const;

 private:
  struct Link {
    int to;
    double cost_in;
    bool is_join;
  };
  int Vertex(int ring, int node) const { return node_offset_[ring] + node; }
  struct SearchEnds;  // where one query's search starts and ends
  struct SearchTree;  // the shortest-path tree it grows

  // ParseGoal() by the form of the name.
  GoalResult ParsePatternGoal(std::string_view name, std::string_view pattern) const;
  GoalResult ParseRingGoal(std::string_view name) const;
  // Plan() in steps: check the query, search the graph, walk the path back into legs.
  bool PoseOnMap(const MapPose& pose) const;
  bool GoalOnMap(const Goal& goal) const;
  SearchEnds Ends(const MapPose& pose, const Goal& goal, double start_metric, double pos) const;
  SearchTree Search(const SearchEnds& ends) const;
  Route RouteAlong(const MapPose& pose, const Goal& goal, const SearchEnds& ends,
                   const SearchTree& tree) const;
  // Direction of a step along one ring, from node u to node w (vertices).
  int StepDir(int u, int w) const;

  const map::Map& map_;
  std::vector<int> node_offset_;
  std::vector<int> ring_of_vertex_;
  std::vector<std::vector<Link>> links_;
};

}  // namespace stickrep::executive
