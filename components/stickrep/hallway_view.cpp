#include "stickrep/hallway_view.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "common/units.h"

namespace stickrep::map {

namespace {

bool IsCorner(double angle_deg) { return std::abs(angle_deg - 180.0) > 1.0; }

// The edge before e in ring order; -1 before the first edge of an open ring.
int PrevEdge(const Ring& ring, int e) {
  const int n = ring.EdgeCount();
  return ring.closed ? (e - 1 + n) % n : e - 1;
}

// The map's joins between the view nodes that stand for their nodes (node_of: [ring]
// [original node] -> view node).
std::vector<Join> ViewJoins(const Map& map, const std::vector<std::vector<int>>& node_of) {
  std::vector<Join> joins;
  for (Join j : map.joins()) {
    const int from = map.FindRing(j.ring), to = map.FindRing(j.to_ring);
    j.node = node_of[from][j.node];
    j.to_node = node_of[to][j.to_node];
    joins.push_back(j);
  }
  return joins;
}

}  // namespace

double HallwayView::HallwayWidthIn(int r) const {
  return original_.ring(r).width_in.value_or(config_.hallway_width_in);
}

double HallwayView::WidestSeenDoorIn(int r) const {
  if (config_.camera_fov_deg <= 0.0) return std::numeric_limits<double>::infinity();
  const double width = HallwayWidthIn(r);
  const double half_fov = DegToRad(0.5 * config_.camera_fov_deg);
  return width * std::tan(half_fov) - config_.door_view_margin_in;  // 2 (width / 2) tan
}

Edge HallwayView::Sensed(int r, int index) const {
  const Ring& ring = original_.ring(r);
  const Edge& e = ring.edges[index];
  if (e.IsOpening()) {
    // A corridor's open end stays an opening: the robot leaves the ring through it. Any
    // other opening is passed along the wall.
    const double after = ring.nodes[(index + 1) % ring.NodeCount()].angle_deg;
    if (IsOpenEnd(e, ring.nodes[index].angle_deg, after)) return e;
    return Edge::Wall(e.metric_in);
  }
  if (!e.IsDoor()) return e;
  Edge door = e;
  if (config_.sensed_door_class) {
    // A width the detector rejects keeps the map's class: the detector's width error still
    // lets it see some of those doors, as the nearest class.
    const std::optional<DoorClass> c = config_.sensed_door_class(e.metric_in);
    if (c) door.door_class = *c;
  }
  const double leaf_in = IsDoubleDoor(*door.door_class) ? 0.5 * e.metric_in : e.metric_in;
  if (leaf_in > WidestSeenDoorIn(r)) return Edge::Wall(e.metric_in);
  return door;
}

double HallwayView::BendTravelIn(int r, const Node& bend) const {
  // The base follows a bend of the wall on a path parallel to it, half the hallway's width
  // out. At a bend that turns the wall toward the free space (angle over 180°: the base
  // turns left, inside the bend) that path is shorter than the wall by 2 d tan(turn / 2);
  // at one that turns away (under 180°, the base outside it) longer by as much.
  const double d = 0.5 * HallwayWidthIn(r);
  return -2.0 * d * std::tan(DegToRad(0.5 * (bend.angle_deg - 180.0)));
}

bool HallwayView::WallLike(int r, int e) const { return Sensed(r, e).IsWall(); }

bool HallwayView::IsStep(int r, int e) const {
  const Ring& ring = original_.ring(r);
  const int n = ring.EdgeCount();
  if (!ring.closed && (e == 0 || e == n - 1)) return false;  // an end of an open ring
  const Edge& edge = ring.edges[e];
  if (!edge.IsWall() || edge.metric_in >= config_.max_step_in) return false;
  const Node& a = ring.nodes[e];
  const Node& b = ring.nodes[(e + 1) % ring.NodeCount()];
  if (a.artificial || b.artificial) return false;
  // Opposite turns: the wall steps across and carries on parallel to itself.
  return IsCorner(a.angle_deg) && IsCorner(b.angle_deg) &&
         std::abs(a.angle_deg + b.angle_deg - 360.0) < 1.0;
}

bool HallwayView::IsRecessSide(int r, int e) const {
  if (config_.max_recess_in <= 0.0) return false;
  const Ring& ring = original_.ring(r);
  const int n = ring.EdgeCount(), nodes = ring.NodeCount();
  const Edge& side = ring.edges[e];
  const Node& a = ring.nodes[e];
  const Node& b = ring.nodes[(e + 1) % nodes];
  if (!side.IsWall() || a.artificial || b.artificial) return false;
  if (!IsCorner(a.angle_deg) || std::abs(a.angle_deg + b.angle_deg - 360.0) >= 1.0) return false;
  // Shallower steps are IsStep's, whichever way they turn.
  if (side.metric_in < config_.max_step_in) return false;
  if (side.metric_in >= HallwayWidthIn(r)) return false;
  // Entering (a convex corner, then a concave one: the wall turns away from the hallway) the
  // recess lies ahead in ring order; leaving it, behind.
  const int dir = a.angle_deg < 180.0 ? +1 : -1;
  double back_in = 0.0;
  for (int k = e + dir, walked = 0; walked < n; k += dir, ++walked) {
    if (!ring.closed && (k < 0 || k >= n)) return false;
    k = (k + n) % n;
    if (k == e) return false;
    const Node& behind = ring.nodes[dir > 0 ? k : (k + 1) % nodes];  // between k and the last
    if (behind.artificial) return false;
    if (walked > 0 && IsCorner(behind.angle_deg)) {
      // The other side: the same depth, turned back the other way.
      const Edge& other = ring.edges[k];
      const Node& far = ring.nodes[dir > 0 ? (k + 1) % nodes : k];
      if (!other.IsWall() || far.artificial || back_in <= 0.0 ||
          std::abs(other.metric_in - side.metric_in) >= 1.0 ||
          std::abs(behind.angle_deg - (dir > 0 ? b.angle_deg : a.angle_deg)) >= 1.0 ||
          std::abs(far.angle_deg - (dir > 0 ? a.angle_deg : b.angle_deg)) >= 1.0) {
        return false;
      }
      // The wall either side is the one the follower tracks: together longer than the
      // recess (else the "recess" is the wall between two blocks standing out from it, and
      // the follower turns at each block).
      const int entry = dir > 0 ? e : k, exit = dir > 0 ? k : e;
      if (!ring.closed && (entry == 0 || exit == n - 1)) return false;
      const double outside_in =
          ring.edges[(entry - 1 + n) % n].metric_in + ring.edges[(exit + 1) % n].metric_in;
      return outside_in >= back_in;
    }
    const Edge& piece = ring.edges[k];
    if (!piece.IsWall() && !piece.IsDoor()) return false;
    back_in += piece.metric_in;
    if (back_in > config_.max_recess_in) return false;
  }
  return false;
}

std::vector<bool> HallwayView::StepEdges(int r) const {
  const int n = original_.ring(r).EdgeCount();
  std::vector<bool> step(n);
  for (int e = 0; e < n; ++e) {
    step[e] = (config_.max_step_in > 0.0 && IsStep(r, e)) || IsRecessSide(r, e);
  }
  return step;
}

bool HallwayView::Merges(int r, const std::vector<bool>& step, int e) const {
  const Ring& ring = original_.ring(r);
  if (step[e]) return false;
  int p = PrevEdge(ring, e);
  if (p < 0) return false;
  if (!step[p]) {
    // A bend the follower follows without turning: between two wall-like edges.
    const Node& node = ring.nodes[e];
    const bool bend = !node.artificial && std::abs(node.angle_deg - 180.0) <= config_.max_bend_deg;
    return bend && WallLike(r, p) && WallLike(r, e);
  }
  while (p >= 0 && step[p] && p != e) p = ring.closed || p > 0 ? PrevEdge(ring, p) : -1;
  return p >= 0 && p != e && WallLike(r, p) && WallLike(r, e);
}

int HallwayView::StartEdge(int r, const std::vector<bool>& step) const {
  const Ring& ring = original_.ring(r);
  const int n = ring.EdgeCount();
  // Start at a kept edge that begins a view edge.
  int start = -1;
  for (int e = 0; e < n && start < 0; ++e) {
    if (!step[e] && !Merges(r, step, e)) start = e;
  }
  if (start < 0) {  // every boundary merges (walls and steps only): keep them apart
    for (int e = 0; e < n && start < 0; ++e) {
      if (!step[e]) start = e;
    }
  }
  if (start < 0) {
    throw std::invalid_argument("ring '" + ring.id + "' has only steps");
  }
  if (!ring.closed) start = 0;  // edge 0 of an open ring is never a step
  return start;
}

Node HallwayView::ViewNode(int r, const std::vector<bool>& step, int e) const {
  const Ring& ring = original_.ring(r);
  Node node = ring.nodes[e];
  const int before = PrevEdge(ring, e);
  if (before >= 0 && step[before]) node.angle_deg = 180.0;  // the step's corner is gone
  if (std::abs(node.angle_deg - 180.0) > config_.max_bend_deg) {
    node.angle_deg = node.angle_deg < 180.0 ? 90.0 : 270.0;  // the turn the follower makes
  }
  return node;
}

Ring HallwayView::CollapseRing(int r, std::vector<int>* node_of) {
  const Ring& ring = original_.ring(r);
  const int n = ring.EdgeCount();
  std::vector<bool> step = StepEdges(r);
  const int start = StartEdge(r, step);
  Ring out;
  out.id = ring.id;
  out.closed = ring.closed;
  std::vector<std::vector<int>> members;
  std::vector<int> view_of(n, -1);
  node_of->assign(ring.NodeCount(), -1);
  // Original edge e becomes part of the last view edge.
  const auto join_last = [&](int e) {
    members.back().push_back(e);
    view_of[e] = static_cast<int>(members.size()) - 1;
  };
  for (int k = 0; k < n; ++k) {
    const int e = (start + k) % n;
    if (step[e]) {
      // A step belongs to the view edge before it.
      if (!members.empty()) join_last(e);
      steps_removed_++;
      continue;
    }
    if (!members.empty() && k > 0 && Merges(r, step, e)) {
      out.edges.back().metric_in += ring.edges[e].metric_in;
      if (!step[PrevEdge(ring, e)]) out.edges.back().metric_in += BendTravelIn(r, ring.nodes[e]);
      join_last(e);
      continue;
    }
    (*node_of)[e] = static_cast<int>(out.nodes.size());
    out.nodes.push_back(ViewNode(r, step, e));
    out.edges.push_back(Sensed(r, e));
    members.push_back({e});
    view_of[e] = static_cast<int>(members.size()) - 1;
  }
  // Steps before the first kept edge of a closed ring close the last view edge.
  for (int e = 0; e < n; ++e) {
    if (view_of[e] < 0) join_last(e);
  }
  if (!ring.closed) {
    (*node_of)[n] = static_cast<int>(out.nodes.size());
    out.nodes.push_back(ring.nodes[n]);
  }
  // A node that is gone (a step's corner, a merged wall's joint) stands for the view node
  // that begins the view edge it lies in: a join there (a hallway branching off beside a
  // pilaster) is reached where the follower, passing the step straight, senses that wall.
  for (int e = 0; e < n; ++e) {
    if ((*node_of)[e] < 0) (*node_of)[e] = view_of[e];
  }
  members_.push_back(std::move(members));
  view_of_.push_back(std::move(view_of));
  step_.push_back(std::move(step));
  return out;
}

HallwayView::HallwayView(const Map& map, HallwayViewConfig config)
    : config_(config), original_(map) {
  std::vector<Ring> rings;
  // [ring][original node] -> view node, for the joins; -1 when the node is gone.
  std::vector<std::vector<int>> node_of(map.RingCount());
  for (int r = 0; r < map.RingCount(); ++r) rings.push_back(CollapseRing(r, &node_of[r]));
  view_ = Map(map.info(), std::move(rings), ViewJoins(map, node_of));
}

HallwayView::Place HallwayView::ToOriginal(int ring, int edge, int dir, double offset_in) const {
  const std::vector<int>& m = members_[ring][edge];
  std::vector<int> along;
  for (int e : m) {
    if (!step_[ring][e]) along.push_back(e);
  }
  if (dir < 0) std::reverse(along.begin(), along.end());
  // The view's length is what the odometer travels (bends add or take some): scale to the
  // walls' own lengths.
  double walls_in = 0.0;
  for (int e : along) walls_in += original_.ring(ring).edges[e].metric_in;
  const double travel_in = view_.ring(ring).edges[edge].metric_in;
  double left = std::max(0.0, offset_in) * (travel_in > 0.0 ? walls_in / travel_in : 1.0);
  for (size_t i = 0; i < along.size(); ++i) {
    const double len = original_.ring(ring).edges[along[i]].metric_in;
    if (left <= len || i + 1 == along.size()) return {along[i], std::min(left, len)};
    left -= len;
  }
  return {m.front(), 0.0};
}

}  // namespace stickrep::map
