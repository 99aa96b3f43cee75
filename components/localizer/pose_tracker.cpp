#include "localizer/pose_tracker.h"

#include <algorithm>
#include <cmath>

namespace stickrep::localizer {

const char* ToString(TrackStatus s) {
  switch (s) {
    case TrackStatus::kIdle:
      return "IDLE";
    case TrackStatus::kTracking:
      return "TRACKING";
    case TrackStatus::kLost:
      return "LOST";
  }
  return "?";
}

PoseTracker::PoseTracker(const map::Map& map, PoseTrackerConfig config)
    : map_(map), config_(config) {}

bool PoseTracker::Start(const TrackedPose& pose, double odometer_in, int odometer_sign) {
  if (pose.ring < 0 || pose.ring >= map_.RingCount() || pose.edge < 0 ||
      pose.edge >= map_.ring(pose.ring).EdgeCount() || (pose.dir != 1 && pose.dir != -1) ||
      (odometer_sign != 1 && odometer_sign != -1) || !std::isfinite(pose.offset_in) ||
      !std::isfinite(odometer_in)) {
    status_ = TrackStatus::kIdle;
    message_ = "cannot track: the pose is not on the map";
    return false;
  }
  const double metric = map_.ring(pose.ring).edges[pose.edge].metric_in;
  anchor_ = map::Cursor{pose.ring, pose.edge, pose.dir};
  odometer_sign_ = odometer_sign;
  anchor_odometer_in_ = odometer_in - odometer_sign * std::clamp(pose.offset_in, 0.0, metric);
  odometer_in_ = odometer_in;
  confirmed_odometer_in_ = odometer_in;
  next_steps_ = 0;
  consecutive_misses_ = 0;
  status_ = TrackStatus::kTracking;
  message_ = "tracking from " + Where(anchor_);
  return true;
}

std::optional<PoseTracker::Ahead> PoseTracker::EdgeAhead(int steps) const {
  Ahead a;
  a.cursor = anchor_;
  for (int i = 0; i < steps; ++i) {
    a.start_in += map_.EdgeAt(a.cursor.ring, a.cursor.edge).metric_in;
    if (!map_.Advance(a.cursor)) return std::nullopt;
  }
  a.edge = &map_.EdgeAt(a.cursor.ring, a.cursor.edge);
  return a;
}

double PoseTracker::UncertaintyAt(double odometer_in) const {
  return config_.uncertainty_base_in +
         config_.uncertainty_per_travel * std::abs(odometer_in - confirmed_odometer_in_);
}

double PoseTracker::uncertainty_in() const { return UncertaintyAt(odometer_in_); }

std::string PoseTracker::Where(const map::Cursor& c) const {
  return map_.ring(c.ring).id + "/" + std::to_string(c.edge) + (c.dir > 0 ? " (+)" : " (-)");
}

TrackedPose PoseTracker::pose() const {
  TrackedPose p;
  map::Cursor c = anchor_;
  double along = std::max(0.0, TravelPastAnchor(odometer_in_));
  while (true) {
    const double metric = map_.EdgeAt(c.ring, c.edge).metric_in;
    if (along < metric) break;
    map::Cursor next = c;
    if (!map_.Advance(next)) {
      along = metric;  // the end of an open ring: stay at its last node
      break;
    }
    along -= metric;
    c = next;
  }
  p.ring = c.ring;
  p.edge = c.edge;
  p.dir = c.dir;
  p.offset_in = along;
  return p;
}

std::optional<map::Cursor> PoseTracker::anticipated() const {
  if (status_ != TrackStatus::kTracking) return std::nullopt;
  const std::optional<Ahead> a = EdgeAhead(next_steps_);
  if (!a) return std::nullopt;
  return a->cursor;
}

void PoseTracker::Miss(const std::string& why) {
  ++misses_;
  ++consecutive_misses_;
  message_ = why;
  if (consecutive_misses_ > config_.max_consecutive_misses) {
    status_ = TrackStatus::kLost;
    message_ = "LOST after " + std::to_string(consecutive_misses_) +
               " consecutive misses (last: " + why + ")";
  }
}

void PoseTracker::Confirm(const Ahead& a, int steps, double end_odometer_in,
                          const std::string& what) {
  // Doors passed over on the way were missed; the confirmation ends the run of misses.
  for (int s = next_steps_; s < steps; ++s) {
    const std::optional<Ahead> skipped = EdgeAhead(s);
    if (skipped && skipped->edge->IsDoor()) ++misses_;
  }
  map::Cursor next = a.cursor;
  const bool more = map_.Advance(next);
  anchor_ = more ? next : a.cursor;
  // At the end of an open ring the anchor stays on the last edge, which then starts one
  // metric before the sensed end.
  anchor_odometer_in_ =
      more ? end_odometer_in : end_odometer_in - odometer_sign_ * a.edge->metric_in;
  next_steps_ = more ? 0 : 1;
  confirmed_odometer_in_ = end_odometer_in;
  consecutive_misses_ = 0;
  ++confirmations_;
  message_ = "confirmed " + what + " at " + Where(a.cursor);
}

void PoseTracker::Advance(double odometer_in) {
  if (!std::isfinite(odometer_in)) return;
  odometer_in_ = odometer_in;
  if (status_ != TrackStatus::kTracking) return;
  const double along = TravelPastAnchor(odometer_in);
  const double radius = UncertaintyAt(odometer_in);
  // Anticipated doors the robot has passed without reporting them.
  for (int s = next_steps_; s <= next_steps_ + config_.lookahead_edges; ++s) {
    const std::optional<Ahead> a = EdgeAhead(s);
    if (!a) break;
    if (a->start_in > along) break;
    if (!a->edge->IsDoor()) continue;
    const double centre = a->start_in + a->edge->metric_in / 2.0;
    if (along <= centre + config_.report_delay_in + radius) break;
    next_steps_ = s + 1;
    Miss(std::string("anticipated ") + map::SymbolName(map::CodeOf(*a->edge)) + " at " +
         Where(a->cursor) + " not seen");
    if (status_ != TrackStatus::kTracking) return;
  }
}

void PoseTracker::OnEdge(const map::SensedEdge& edge, double end_odometer_in) {
  if (status_ != TrackStatus::kTracking || !std::isfinite(end_odometer_in)) return;
  const double end = TravelPastAnchor(end_odometer_in);
  const double radius = UncertaintyAt(end_odometer_in);
  const bool door = map::IsDoorCode(edge.code);
  // The anticipated edge (or one a few past it) whose end is nearest the sensed end.
  std::optional<Ahead> best;
  int best_steps = 0;
  double best_error = radius;
  for (int s = next_steps_; s <= next_steps_ + config_.lookahead_edges; ++s) {
    const std::optional<Ahead> a = EdgeAhead(s);
    if (!a) break;
    if (a->start_in > end + radius) break;
    const map::SymbolCode code = map::CodeOf(*a->edge);
    if (door ? !map::IsDoorCode(code) : code != edge.code) continue;
    const double error = std::abs(a->start_in + a->edge->metric_in - end);
    if (error > best_error) continue;
    if (!door) {
      const double m = a->edge->metric_in;
      const double allow = std::max(config_.wall_tolerance_abs_in, config_.wall_tolerance_rel * m);
      const bool fits = edge.metric_is_lower_bound ? m >= edge.metric_in - allow
                                                   : std::abs(m - edge.metric_in) <= allow;
      if (!fits) continue;
    }
    best = a;
    best_steps = s;
    best_error = error;
  }
  const std::string name = map::SymbolName(edge.code);
  if (!best) {
    // Walls are judged through the doors that bound them (see the class comment).
    if (door) Miss("sensed " + name + " where the map has no door (false door)");
    return;
  }
  if (door && map::CodeOf(*best->edge) != edge.code) {
    next_steps_ = best_steps + 1;
    Miss("sensed " + name + " where the map has " + map::SymbolName(map::CodeOf(*best->edge)) +
         " at " + Where(best->cursor) + " (mis-sized door)");
    return;
  }
  Confirm(*best, best_steps, end_odometer_in, name);
}

void PoseTracker::OnEdges(const std::vector<map::SensedEdge>& edges, double last_end_odometer_in) {
  // Ends of the earlier edges: walk back from the last one by the later edges' metrics.
  std::vector<double> ends(edges.size());
  double end = last_end_odometer_in;
  for (std::size_t i = edges.size(); i-- > 0;) {
    ends[i] = end;
    const map::SensedEdge& e = edges[i];
    double metric = e.metric_in;
    if (map::IsDoorCode(e.code) && !(metric > 0.0)) {
      metric = map::DoorClassWidthIn(static_cast<map::DoorClass>(e.code - 1));
    }
    end -= odometer_sign_ * metric;
  }
  for (std::size_t i = 0; i < edges.size(); ++i) OnEdge(edges[i], ends[i]);
}

}  // namespace stickrep::localizer
