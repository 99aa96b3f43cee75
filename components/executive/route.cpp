#include "executive/route.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <queue>

namespace stickrep::executive {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string_view Trim(std::string_view s) {
  const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
  while (!s.empty() && space(s.front())) s.remove_prefix(1);
  while (!s.empty() && space(s.back())) s.remove_suffix(1);
  return s;
}

// A non-negative decimal index, digits only; nullopt otherwise.
std::optional<int> ParseIndex(std::string_view s) {
  if (s.empty() || s.size() > 9) return std::nullopt;
  int value = 0;
  for (char c : s) {
    if (c < '0' || c > '9') return std::nullopt;
    value = value * 10 + (c - '0');
  }
  return value;
}

std::string Fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}

// The node at the end of edge `edge` in ring order.
int EdgeEndNode(const map::Ring& ring, int edge) { return (edge + 1) % ring.NodeCount(); }

constexpr char kGoalForms[] = "expected RING/EDGE, RING/node/NODE or pattern:NAME";

// How an error message names the goal it is about.
std::string Quoted(std::string_view name) { return "goal '" + std::string(name) + "': "; }

GoalResult GoalError(std::string error) {
  GoalResult out;
  out.error = std::move(error);
  return out;
}

GoalResult GoalAt(std::string_view name, GoalKind kind, int ring, int index) {
  Goal goal;
  goal.name = std::string(name);
  goal.kind = kind;
  goal.ring = ring;
  goal.index = index;
  GoalResult out;
  out.goal = goal;
  return out;
}

// The parts of `name` between slashes, empty ones included.
std::vector<std::string_view> SplitAtSlashes(std::string_view name) {
  std::vector<std::string_view> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t slash = name.find('/', start);
    parts.push_back(name.substr(start, slash == std::string_view::npos ? slash : slash - start));
    if (slash == std::string_view::npos) break;
    start = slash + 1;
  }
  return parts;
}

// A goal in the edge the robot is in: straight to its midpoint, no search.
Route SameEdgeRoute(const MapPose& pose, const Goal& goal, double start_metric, double pos) {
  Route route;
  route.goal = goal;
  const double mid = start_metric / 2.0;
  RouteLeg leg;
  leg.ring = pose.ring;
  leg.dir = mid >= pos ? +1 : -1;
  leg.distance_in = std::abs(mid - pos);
  route.legs.push_back(leg);
  route.distance_in = leg.distance_in;
  route.initial_travel_sign = leg.distance_in > 1e-9 ? leg.dir * pose.dir : 0;
  return route;
}

// Vertices from the first node to the goal.
std::vector<int> PathTo(const std::vector<int>& prev, int goal_vertex) {
  std::vector<int> path;
  for (int v = goal_vertex; v != -1; v = prev[v]) path.push_back(v);
  std::reverse(path.begin(), path.end());
  return path;
}

// The next step along the ring goes direction `dir`: if that turns the travel round, the
// leg so far ends at `turn_node` and a new one starts there (a leg with no length yet just
// takes the new direction).
void TurnLeg(int dir, int turn_node, RouteLeg* leg, Route* route) {
  if (dir != leg->dir && leg->distance_in > 1e-9) {
    leg->end_node = turn_node;
    route->legs.push_back(*leg);
    *leg = RouteLeg{leg->ring, dir, 0.0, -1};
  }
}

}  // namespace

RoutePlanner::RoutePlanner(const map::Map& map) : map_(map) {
  int vertices = 0;
  for (const map::Ring& ring : map_.rings()) {
    node_offset_.push_back(vertices);
    vertices += ring.NodeCount();
  }
  links_.resize(vertices);
  ring_of_vertex_.resize(vertices);
  for (int r = 0; r < map_.RingCount(); ++r) {
    const map::Ring& ring = map_.ring(r);
    for (int n = 0; n < ring.NodeCount(); ++n) ring_of_vertex_[Vertex(r, n)] = r;
    for (int e = 0; e < ring.EdgeCount(); ++e) {
      const int a = Vertex(r, e);
      const int b = Vertex(r, EdgeEndNode(ring, e));
      links_[a].push_back({b, ring.edges[e].metric_in, false});
      links_[b].push_back({a, ring.edges[e].metric_in, false});
    }
  }
  for (const map::Join& j : map_.joins()) {
    const int r1 = map_.FindRing(j.ring);
    const int r2 = map_.FindRing(j.to_ring);
    if (r1 < 0 || r2 < 0) continue;  // the Map constructor has checked this already
    const map::Node& n1 = map_.ring(r1).nodes[j.node];
    const map::Node& n2 = map_.ring(r2).nodes[j.to_node];
    const double d = std::hypot(n1.x_in - n2.x_in, n1.y_in - n2.y_in, n1.z_in - n2.z_in);
    links_[Vertex(r1, j.node)].push_back({Vertex(r2, j.to_node), d, true});
    links_[Vertex(r2, j.to_node)].push_back({Vertex(r1, j.node), d, true});
  }
}

GoalResult RoutePlanner::ParseGoal(std::string_view raw) const {
  const std::string_view name = Trim(raw);
  if (name.empty()) return GoalError("empty goal name: " + std::string(kGoalForms));
  constexpr std::string_view kPattern = "pattern:";
  if (name.substr(0, kPattern.size()) == kPattern) {
    return ParsePatternGoal(name, name.substr(kPattern.size()));
  }
  return ParseRingGoal(name);
}

GoalResult RoutePlanner::ParsePatternGoal(std::string_view name, std::string_view pattern) const {
  const std::string quoted = Quoted(name);
  if (pattern.empty()) return GoalError(quoted + "no pattern after 'pattern:'");
  std::vector<std::pair<int, int>> hits;
  for (int r = 0; r < map_.RingCount(); ++r) {
    const map::Ring& ring = map_.ring(r);
    for (int e = 0; e < ring.EdgeCount(); ++e) {
      if (ring.edges[e].pattern == pattern) hits.emplace_back(r, e);
    }
  }
  if (hits.empty()) {
    return GoalError(quoted + "no edge of map '" + map_.info().name + "' has pattern '" +
                     std::string(pattern) + "'");
  }
  if (hits.size() > 1) {
    std::string where;
    for (std::size_t i = 0; i < hits.size() && i < 3; ++i) {
      where += (i ? ", " : "") + map_.ring(hits[i].first).id + "/" + std::to_string(hits[i].second);
    }
    if (hits.size() > 3) where += ", ...";
    return GoalError(quoted + "pattern '" + std::string(pattern) + "' is on " +
                     std::to_string(hits.size()) + " edges (" + where +
                     "): name the edge as RING/EDGE");
  }
  return GoalAt(name, GoalKind::kEdge, hits[0].first, hits[0].second);
}

GoalResult RoutePlanner::ParseRingGoal(std::string_view name) const {
  const std::string quoted = Quoted(name);
  const std::vector<std::string_view> parts = SplitAtSlashes(name);
  const bool edge_form = parts.size() == 2;
  const bool node_form = parts.size() == 3 && parts[1] == "node";
  if (!edge_form && !node_form) return GoalError(quoted + "malformed: " + kGoalForms);
  const int r = map_.FindRing(parts[0]);
  if (r < 0) {
    return GoalError(quoted + "map '" + map_.info().name + "' has no ring '" +
                     std::string(parts[0]) + "'");
  }
  const std::optional<int> index = ParseIndex(parts.back());
  if (!index) {
    return GoalError(quoted + "'" + std::string(parts.back()) +
                     "' is not an index (digits only, counting from 0)");
  }
  const map::Ring& ring = map_.ring(r);
  const int count = edge_form ? ring.EdgeCount() : ring.NodeCount();
  if (*index >= count) {
    return GoalError(quoted + (edge_form ? "edge " : "node ") + std::to_string(*index) +
                     " is out of range: ring '" + ring.id + "' has " + std::to_string(count) +
                     (edge_form ? " edges" : " nodes"));
  }
  return GoalAt(name, edge_form ? GoalKind::kEdge : GoalKind::kNode, r, *index);
}

RouteResult RoutePlanner::Plan(const MapPose& pose, std::string_view goal_name) const {
  GoalResult g = ParseGoal(goal_name);
  if (!g) return RouteResult{std::nullopt, g.error};
  return Plan(pose, *g.goal);
}

// The search graph's ends for one query: the start edge's two nodes, at their distances
// from the pose, and the goal vertex. An edge goal is an extra vertex (index: the vertex
// count) at the edge's midpoint, linked from the edge's two nodes.
struct RoutePlanner::SearchEnds {
  int start_a = -1;  // the start edge's first node in ring order
  int start_b = -1;  // and its last
  double start_a_in = 0.0;
  double start_b_in = 0.0;
  int goal_vertex = -1;
  int goal_a = -1;  // an edge goal's two nodes; -1 for a node goal
  int goal_b = -1;
  double goal_half_in = 0.0;  // from either of them to the midpoint
};

// Dijkstra's shortest-path tree, over the ring nodes plus the edge goal's vertex.
struct RoutePlanner::SearchTree {
  std::vector<double> dist;
  std::vector<int> prev;  // -1: reached from the start
  std::vector<bool> prev_is_join;
};

RouteResult RoutePlanner::Plan(const MapPose& pose, const Goal& goal) const {
  RouteResult out;
  if (!PoseOnMap(pose)) {
    out.error = "pose is not on the map: ring " + std::to_string(pose.ring) + " edge " +
                std::to_string(pose.edge) + " dir " + std::to_string(pose.dir);
    return out;
  }
  if (!GoalOnMap(goal)) {
    out.error = "goal '" + goal.name + "' is not on the map";
    return out;
  }
  const map::Ring& start_ring = map_.ring(pose.ring);
  const double start_metric = start_ring.edges[pose.edge].metric_in;
  // Position inside the start edge in ring order (the offset counts in travel direction).
  const double offset = std::clamp(pose.offset_in, 0.0, start_metric);
  const double pos = pose.dir > 0 ? offset : start_metric - offset;

  // Same edge: straight there.
  if (goal.kind == GoalKind::kEdge && goal.ring == pose.ring && goal.index == pose.edge) {
    out.route = SameEdgeRoute(pose, goal, start_metric, pos);
    return out;
  }

  const SearchEnds ends = Ends(pose, goal, start_metric, pos);
  const SearchTree tree = Search(ends);
  if (!std::isfinite(tree.dist[ends.goal_vertex])) {
    out.error = "goal '" + goal.name + "' cannot be reached from ring '" + start_ring.id +
                "': no join leads to ring '" + map_.ring(goal.ring).id + "'";
    return out;
  }
  out.route = RouteAlong(pose, goal, ends, tree);
  return out;
}

bool RoutePlanner::PoseOnMap(const MapPose& pose) const {
  return !(pose.ring < 0 || pose.ring >= map_.RingCount() || pose.edge < 0 ||
           pose.edge >= map_.ring(pose.ring).EdgeCount() || (pose.dir != 1 && pose.dir != -1) ||
           !std::isfinite(pose.offset_in));
}

bool RoutePlanner::GoalOnMap(const Goal& goal) const {
  return !(goal.ring < 0 || goal.ring >= map_.RingCount() || goal.index < 0 ||
           goal.index >= (goal.kind == GoalKind::kEdge ? map_.ring(goal.ring).EdgeCount()
                                                       : map_.ring(goal.ring).NodeCount()));
}

RoutePlanner::SearchEnds RoutePlanner::Ends(const MapPose& pose, const Goal& goal,
                                            double start_metric, double pos) const {
  SearchEnds ends;
  const int vertices = static_cast<int>(links_.size());
  ends.goal_vertex = goal.kind == GoalKind::kNode ? Vertex(goal.ring, goal.index) : vertices;
  if (goal.kind == GoalKind::kEdge) {
    const map::Ring& ring = map_.ring(goal.ring);
    ends.goal_a = Vertex(goal.ring, goal.index);
    ends.goal_b = Vertex(goal.ring, EdgeEndNode(ring, goal.index));
    ends.goal_half_in = ring.edges[goal.index].metric_in / 2.0;
  }
  ends.start_a = Vertex(pose.ring, pose.edge);
  ends.start_b = Vertex(pose.ring, EdgeEndNode(map_.ring(pose.ring), pose.edge));
  ends.start_a_in = pos;
  ends.start_b_in = start_metric - pos;
  return ends;
}

RoutePlanner::SearchTree RoutePlanner::Search(const SearchEnds& ends) const {
  const int vertices = static_cast<int>(links_.size());
  SearchTree tree;
  std::vector<double>& dist = tree.dist;
  dist.assign(vertices + 1, kInf);
  tree.prev.assign(vertices + 1, -1);
  tree.prev_is_join.assign(vertices + 1, false);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  auto seed = [&](int v, double d) {
    if (d < dist[v]) {
      dist[v] = d;
      queue.push({d, v});
    }
  };
  seed(ends.start_a, ends.start_a_in);
  seed(ends.start_b, ends.start_b_in);
  auto relax = [&](int from, int to, double cost, bool join) {
    if (dist[from] + cost < dist[to]) {
      dist[to] = dist[from] + cost;
      tree.prev[to] = from;
      tree.prev_is_join[to] = join;
      queue.push({dist[to], to});
    }
  };
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > dist[v] || v == ends.goal_vertex) {
      if (v == ends.goal_vertex) break;
      continue;
    }
    for (const Link& l : links_[v]) relax(v, l.to, l.cost_in, l.is_join);
    if (v == ends.goal_a || v == ends.goal_b) relax(v, vertices, ends.goal_half_in, false);
  }
  return tree;
}

Route RoutePlanner::RouteAlong(const MapPose& pose, const Goal& goal, const SearchEnds& ends,
                               const SearchTree& tree) const {
  const int vertices = static_cast<int>(links_.size());
  const std::vector<double>& dist = tree.dist;
  const std::vector<int> path = PathTo(tree.prev, ends.goal_vertex);
  Route route;
  route.goal = goal;
  RouteLeg leg;
  leg.ring = pose.ring;
  leg.dir = path.front() == ends.start_b ? +1 : -1;
  leg.distance_in = dist[path.front()];
  bool leg_has_dir = true;
  for (std::size_t i = 1; i < path.size(); ++i) {
    const int u = path[i - 1], w = path[i];
    const double cost = dist[w] - dist[u];
    if (w == vertices) {  // into the goal edge, to its midpoint
      const int dir = u == ends.goal_a ? +1 : -1;
      if (leg_has_dir) TurnLeg(dir, u - node_offset_[leg.ring], &leg, &route);
      leg.dir = dir;
      leg.distance_in += cost;
      leg.end_node = -1;
      leg_has_dir = true;
      continue;
    }
    if (tree.prev_is_join[w]) {
      leg.end_node = u - node_offset_[leg.ring];
      route.legs.push_back(leg);
      const int r2 = ring_of_vertex_[w];
      route.crossings.push_back(
          {leg.ring, u - node_offset_[leg.ring], r2, w - node_offset_[r2], cost});
      leg = RouteLeg{r2, +1, 0.0, w - node_offset_[r2]};
      leg_has_dir = false;
      continue;
    }
    const int dir = StepDir(u, w);
    if (leg_has_dir) TurnLeg(dir, u - node_offset_[leg.ring], &leg, &route);
    leg.dir = dir;
    leg_has_dir = true;
    leg.distance_in += cost;
    leg.end_node = w - node_offset_[leg.ring];
  }
  route.legs.push_back(leg);
  route.distance_in = dist[ends.goal_vertex];
  const RouteLeg& first = route.legs.front();
  route.initial_travel_sign = first.distance_in > 1e-9 ? first.dir * pose.dir : 0;
  if (route.initial_travel_sign == 0 && !route.crossings.empty()) route.initial_travel_sign = +1;
  return route;
}

int RoutePlanner::StepDir(int u, int w) const {
  const int r = ring_of_vertex_[u];
  const map::Ring& ring = map_.ring(r);
  const int nu = u - node_offset_[r], nw = w - node_offset_[r];
  return (nu + 1) % (ring.closed ? ring.NodeCount() : ring.NodeCount() + 1) == nw ? +1 : -1;
}

std::string RoutePlanner::Describe(const Route& route) const {
  std::string s = "goal '" + route.goal.name + "': " + Fmt(route.distance_in) + " in";
  for (std::size_t i = 0; i < route.legs.size(); ++i) {
    const RouteLeg& leg = route.legs[i];
    s += "; ring " + map_.ring(leg.ring).id +
         (leg.dir > 0 ? " in ring order " : " against ring order ") + Fmt(leg.distance_in) + " in";
    if (i < route.crossings.size()) {
      const JoinCrossing& c = route.crossings[i];
      s += "; cross at node " + std::to_string(c.from_node) + " to ring " +
           map_.ring(c.to_ring).id + " node " + std::to_string(c.to_node) + " (" +
           Fmt(c.distance_in) + " in)";
    }
  }
  return s;
}

}  // namespace stickrep::executive
