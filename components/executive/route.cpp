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
  GoalResult out;
  const std::string_view name = Trim(raw);
  const std::string quoted = "goal '" + std::string(name) + "': ";
  const std::string forms = "expected RING/EDGE, RING/node/NODE or pattern:NAME";
  if (name.empty()) {
    out.error = "empty goal name: " + forms;
    return out;
  }
  Goal goal;
  goal.name = std::string(name);
  constexpr std::string_view kPattern = "pattern:";
  if (name.substr(0, kPattern.size()) == kPattern) {
    const std::string_view pattern = name.substr(kPattern.size());
    if (pattern.empty()) {
      out.error = quoted + "no pattern after 'pattern:'";
      return out;
    }
    std::vector<std::pair<int, int>> hits;
    for (int r = 0; r < map_.RingCount(); ++r) {
      const map::Ring& ring = map_.ring(r);
      for (int e = 0; e < ring.EdgeCount(); ++e) {
        if (ring.edges[e].pattern == pattern) hits.emplace_back(r, e);
      }
    }
    if (hits.empty()) {
      out.error = quoted + "no edge of map '" + map_.info().name + "' has pattern '" +
                  std::string(pattern) + "'";
      return out;
    }
    if (hits.size() > 1) {
      std::string where;
      for (std::size_t i = 0; i < hits.size() && i < 3; ++i) {
        where +=
            (i ? ", " : "") + map_.ring(hits[i].first).id + "/" + std::to_string(hits[i].second);
      }
      if (hits.size() > 3) where += ", ...";
      out.error = quoted + "pattern '" + std::string(pattern) + "' is on " +
                  std::to_string(hits.size()) + " edges (" + where +
                  "): name the edge as RING/EDGE";
      return out;
    }
    goal.kind = GoalKind::kEdge;
    goal.ring = hits[0].first;
    goal.index = hits[0].second;
    out.goal = goal;
    return out;
  }

  std::vector<std::string_view> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t slash = name.find('/', start);
    parts.push_back(name.substr(start, slash == std::string_view::npos ? slash : slash - start));
    if (slash == std::string_view::npos) break;
    start = slash + 1;
  }
  const bool edge_form = parts.size() == 2;
  const bool node_form = parts.size() == 3 && parts[1] == "node";
  if (!edge_form && !node_form) {
    out.error = quoted + "malformed: " + forms;
    return out;
  }
  const int r = map_.FindRing(parts[0]);
  if (r < 0) {
    out.error =
        quoted + "map '" + map_.info().name + "' has no ring '" + std::string(parts[0]) + "'";
    return out;
  }
  const std::optional<int> index = ParseIndex(parts.back());
  if (!index) {
    out.error = quoted + "'" + std::string(parts.back()) +
                "' is not an index (digits only, counting from 0)";
    return out;
  }
  const map::Ring& ring = map_.ring(r);
  const int count = edge_form ? ring.EdgeCount() : ring.NodeCount();
  if (*index >= count) {
    out.error = quoted + (edge_form ? "edge " : "node ") + std::to_string(*index) +
                " is out of range: ring '" + ring.id + "' has " + std::to_string(count) +
                (edge_form ? " edges" : " nodes");
    return out;
  }
  goal.kind = edge_form ? GoalKind::kEdge : GoalKind::kNode;
  goal.ring = r;
  goal.index = *index;
  out.goal = goal;
  return out;
}

RouteResult RoutePlanner::Plan(const MapPose& pose, std::string_view goal_name) const {
  GoalResult g = ParseGoal(goal_name);
  if (!g) return RouteResult{std::nullopt, g.error};
  return Plan(pose, *g.goal);
}

RouteResult RoutePlanner::Plan(const MapPose& pose, const Goal& goal) const {
  RouteResult out;
  if (pose.ring < 0 || pose.ring >= map_.RingCount() || pose.edge < 0 ||
      pose.edge >= map_.ring(pose.ring).EdgeCount() || (pose.dir != 1 && pose.dir != -1) ||
      !std::isfinite(pose.offset_in)) {
    out.error = "pose is not on the map: ring " + std::to_string(pose.ring) + " edge " +
                std::to_string(pose.edge) + " dir " + std::to_string(pose.dir);
    return out;
  }
  if (goal.ring < 0 || goal.ring >= map_.RingCount() || goal.index < 0 ||
      goal.index >= (goal.kind == GoalKind::kEdge ? map_.ring(goal.ring).EdgeCount()
                                                  : map_.ring(goal.ring).NodeCount())) {
    out.error = "goal '" + goal.name + "' is not on the map";
    return out;
  }
  const map::Ring& start_ring = map_.ring(pose.ring);
  const double start_metric = start_ring.edges[pose.edge].metric_in;
  // Position inside the start edge in ring order (the offset counts in travel direction).
  const double offset = std::clamp(pose.offset_in, 0.0, start_metric);
  const double pos = pose.dir > 0 ? offset : start_metric - offset;

  Route route;
  route.goal = goal;

  // Same edge: straight there.
  if (goal.kind == GoalKind::kEdge && goal.ring == pose.ring && goal.index == pose.edge) {
    const double mid = start_metric / 2.0;
    RouteLeg leg;
    leg.ring = pose.ring;
    leg.dir = mid >= pos ? +1 : -1;
    leg.distance_in = std::abs(mid - pos);
    route.legs.push_back(leg);
    route.distance_in = leg.distance_in;
    route.initial_travel_sign = leg.distance_in > 1e-9 ? leg.dir * pose.dir : 0;
    out.route = route;
    return out;
  }

  // Dijkstra over the ring nodes plus a goal vertex for an edge goal (its midpoint).
  const int vertices = static_cast<int>(links_.size());
  const int goal_vertex = goal.kind == GoalKind::kNode ? Vertex(goal.ring, goal.index) : vertices;
  int goal_a = -1, goal_b = -1;
  double goal_half = 0.0;
  if (goal.kind == GoalKind::kEdge) {
    const map::Ring& ring = map_.ring(goal.ring);
    goal_a = Vertex(goal.ring, goal.index);
    goal_b = Vertex(goal.ring, EdgeEndNode(ring, goal.index));
    goal_half = ring.edges[goal.index].metric_in / 2.0;
  }
  std::vector<double> dist(vertices + 1, kInf);
  std::vector<int> prev(vertices + 1, -1);  // -1: reached from the start
  std::vector<bool> prev_is_join(vertices + 1, false);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  const int start_a = Vertex(pose.ring, pose.edge);
  const int start_b = Vertex(pose.ring, EdgeEndNode(start_ring, pose.edge));
  auto seed = [&](int v, double d) {
    if (d < dist[v]) {
      dist[v] = d;
      queue.push({d, v});
    }
  };
  seed(start_a, pos);
  seed(start_b, start_metric - pos);
  auto relax = [&](int from, int to, double cost, bool join) {
    if (dist[from] + cost < dist[to]) {
      dist[to] = dist[from] + cost;
      prev[to] = from;
      prev_is_join[to] = join;
      queue.push({dist[to], to});
    }
  };
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > dist[v] || v == goal_vertex) {
      if (v == goal_vertex) break;
      continue;
    }
    for (const Link& l : links_[v]) relax(v, l.to, l.cost_in, l.is_join);
    if (v == goal_a || v == goal_b) relax(v, vertices, goal_half, false);
  }
  if (!std::isfinite(dist[goal_vertex])) {
    out.error = "goal '" + goal.name + "' cannot be reached from ring '" + start_ring.id +
                "': no join leads to ring '" + map_.ring(goal.ring).id + "'";
    return out;
  }

  // Vertices from the first node to the goal.
  std::vector<int> path;
  for (int v = goal_vertex; v != -1; v = prev[v]) path.push_back(v);
  std::reverse(path.begin(), path.end());

  // Direction of a step along one ring, from node u to node w (vertices).
  auto step_dir = [&](int u, int w) {
    const int r = ring_of_vertex_[u];
    const map::Ring& ring = map_.ring(r);
    const int nu = u - node_offset_[r], nw = w - node_offset_[r];
    return (nu + 1) % (ring.closed ? ring.NodeCount() : ring.NodeCount() + 1) == nw ? +1 : -1;
  };

  RouteLeg leg;
  leg.ring = pose.ring;
  leg.dir = path.front() == start_b ? +1 : -1;
  leg.distance_in = dist[path.front()];
  bool leg_has_dir = true;
  for (std::size_t i = 1; i < path.size(); ++i) {
    const int u = path[i - 1], w = path[i];
    const double cost = dist[w] - dist[u];
    if (w == vertices) {  // into the goal edge, to its midpoint
      const int dir = u == goal_a ? +1 : -1;
      if (leg_has_dir && dir != leg.dir && leg.distance_in > 1e-9) {
        leg.end_node = u - node_offset_[leg.ring];
        route.legs.push_back(leg);
        leg = RouteLeg{leg.ring, dir, 0.0, -1};
      }
      leg.dir = dir;
      leg.distance_in += cost;
      leg.end_node = -1;
      leg_has_dir = true;
      continue;
    }
    if (prev_is_join[w]) {
      leg.end_node = u - node_offset_[leg.ring];
      route.legs.push_back(leg);
      const int r2 = ring_of_vertex_[w];
      route.crossings.push_back(
          {leg.ring, u - node_offset_[leg.ring], r2, w - node_offset_[r2], cost});
      leg = RouteLeg{r2, +1, 0.0, w - node_offset_[r2]};
      leg_has_dir = false;
      continue;
    }
    const int dir = step_dir(u, w);
    if (leg_has_dir && dir != leg.dir && leg.distance_in > 1e-9) {
      leg.end_node = u - node_offset_[leg.ring];
      route.legs.push_back(leg);
      leg = RouteLeg{leg.ring, dir, 0.0, -1};
    }
    leg.dir = dir;
    leg_has_dir = true;
    leg.distance_in += cost;
    leg.end_node = w - node_offset_[leg.ring];
  }
  route.legs.push_back(leg);
  route.distance_in = dist[goal_vertex];
  const RouteLeg& first = route.legs.front();
  route.initial_travel_sign = first.distance_in > 1e-9 ? first.dir * pose.dir : 0;
  if (route.initial_travel_sign == 0 && !route.crossings.empty()) route.initial_travel_sign = +1;
  out.route = route;
  return out;
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
