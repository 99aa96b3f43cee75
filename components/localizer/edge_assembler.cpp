#include "localizer/edge_assembler.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stickrep::localizer {

void EdgeAssembler::AddSighting(const DoorSighting& s) {
  // While the base turns in place the camera sweeps across the corner: no wall is square
  // to it and a sighting has no place along either wall.
  if (corner_ && !corner_->settled) return;
  const double lo = s.along_in - s.width_in / 2.0, hi = s.along_in + s.width_in / 2.0;
  const double weight = std::max(s.confidence, 1e-3);
  for (Track& t : open_) {
    if (std::abs(t.lo() - lo) < config_.same_door_in && std::abs(t.hi() - hi) < config_.same_door_in) {
      t.lo_sum += lo;
      t.hi_sum += hi;
      t.frames++;
      t.support += weight;
      t.class_weight[static_cast<int>(s.door_class)] += weight;
      t.mark_weight[static_cast<int>(s.mark)] += weight;
      return;
    }
  }
  Track t;
  t.lo_sum = lo;
  t.hi_sum = hi;
  t.frames = 1;
  t.support = weight;
  t.class_weight[static_cast<int>(s.door_class)] = weight;
  t.mark_weight[static_cast<int>(s.mark)] = weight;
  open_.push_back(std::move(t));
}

std::optional<double> EdgeAssembler::silent_in() const {
  if (!last_jamb_in_ || corner_ || direction_ == 0) return std::nullopt;
  double reach = odometer_in_ - direction_ * config_.silent_margin_in;
  for (const Track& t : open_) {
    if (direction_ * (Near(t) - reach) < 0.0) reach = Near(t);
  }
  if (held_ && direction_ * (Near(*held_) - reach) < 0.0) reach = Near(*held_);
  return std::max(0.0, direction_ * (reach - *last_jamb_in_));
}

void EdgeAssembler::Restart() {
  open_.clear();
  held_.reset();
  corner_.reset();
  placed_.clear();
  sequence_.clear();
  spans_.clear();
  last_jamb_in_.reset();
  last_door_end_in_.reset();
  pending_angle_deg_ = std::numeric_limits<double>::quiet_NaN();
  start_in_ = odometer_in_;
}

std::vector<map::SensedEdge> EdgeAssembler::Advance(double odometer_in, double heading_rad) {
  std::vector<map::SensedEdge> out;
  if (!have_odometer_) {
    have_odometer_ = true;
    start_in_ = odometer_in;
    odometer_in_ = odometer_in;
  }
  if (direction_ == 0 && std::abs(odometer_in - start_in_) > 1e-6) {
    direction_ = odometer_in > start_in_ ? +1 : -1;
    farthest_in_ = odometer_in;
  }
  odometer_in_ = odometer_in;
  if (direction_ == 0) return out;
  if (direction_ * (odometer_in - farthest_in_) > 0.0) farthest_in_ = odometer_in;
  if (direction_ * (farthest_in_ - odometer_in) > config_.reverse_after_in) {
    // Travelling the other way now: what was being assembled belongs to the old direction.
    reversal_travel_in_ = last_jamb_in_ && !corner_
                              ? direction_ * (farthest_in_ - *last_jamb_in_)
                              : std::numeric_limits<double>::quiet_NaN();
    Restart();
    headings_.clear();
    direction_ = -direction_;
    farthest_in_ = odometer_in;
    reversed_ = true;
    return out;
  }
  out.swap(placed_);
  if (corner_) {
    if (!corner_->settled) {
      if (std::abs(odometer_in_ - corner_->odometer_in) > config_.turn_settled_travel_in) {
        corner_->settled = true;
        corner_->settled_odometer_in = odometer_in_;
        headings_.clear();  // the new wall's heading, as driven, is the reference
      }
    } else if (std::abs(odometer_in_ - corner_->settled_odometer_in) > config_.range_wait_in) {
      PlaceCorner(std::numeric_limits<double>::quiet_NaN(), out);
    }
    if (corner_) return out;  // nothing is placed along the new wall before the corner
  }
  // Complete the tracks the optical axis has left behind, nearest first.
  std::sort(open_.begin(), open_.end(), [this](const Track& a, const Track& b) {
    return direction_ * a.along() < direction_ * b.along();
  });
  while (!open_.empty() &&
         direction_ * (odometer_in_ - open_.front().along()) > config_.out_of_view_in) {
    Track t = open_.front();
    open_.erase(open_.begin());
    Complete(t, out);
  }
  const double turn = TurnOverWindow(heading_rad);
  if (std::abs(turn) * 180.0 / M_PI < config_.turn_settled_deg) {
    if (std::isfinite(unconfirmed_range_in_)) wall_range_in_ = unconfirmed_range_in_;
  }
  unconfirmed_range_in_ = std::numeric_limits<double>::quiet_NaN();
  if (std::abs(turn) * 180.0 / M_PI > config_.corner_turn_deg) {
    // The new reference is taken once the turn is over (Advance, above).
    BeginCorner(turn, out);
  }
  return out;
}

double EdgeAssembler::TurnOverWindow(double heading_rad) {
  // A base standing still adds nothing new: a sample per half inch or degree.
  if (headings_.empty() || std::abs(odometer_in_ - headings_.back().odometer_in) >= 0.5 ||
      std::abs(std::remainder(heading_rad - headings_.back().heading_rad, 2.0 * M_PI)) >=
          M_PI / 180.0) {
    headings_.push_back({odometer_in_, heading_rad});
  }
  // Keep one sample at or beyond the window's far end: the reference.
  while (headings_.size() > 1 &&
         std::abs(odometer_in_ - headings_[1].odometer_in) >= config_.corner_window_in) {
    headings_.pop_front();
  }
  return std::remainder(heading_rad - headings_.front().heading_rad, 2.0 * M_PI);
}

void EdgeAssembler::SetWallRange(double range_in) {
  if (!std::isfinite(range_in) || range_in <= 0.0) return;
  if (corner_ && corner_->settled) {
    std::vector<map::SensedEdge> out;  // emitted edges are kept in sequence_ for Advance
    PlaceCorner(range_in, out);
    placed_.insert(placed_.end(), out.begin(), out.end());
    wall_range_in_ = range_in;
    return;
  }
  // Taken once the next heading shows the base was not turning meanwhile (Advance).
  if (!corner_) unconfirmed_range_in_ = range_in;
}

void EdgeAssembler::BeginCorner(double turn_rad, std::vector<map::SensedEdge>& out) {
  // Every door behind the corner is complete: its frames are all in.
  std::sort(open_.begin(), open_.end(), [this](const Track& a, const Track& b) {
    return direction_ * a.along() < direction_ * b.along();
  });
  while (!open_.empty() && direction_ * (odometer_in_ - open_.front().along()) > 0.0) {
    Track t = open_.front();
    open_.erase(open_.begin());
    Complete(t, out);
  }
  if (held_) Emit(*held_, out);  // its rival lay across the corner
  held_.reset();
  open_.clear();  // anything ahead was seen across the corner, on another wall
  // The wall up to the corner, then the node. The wall on the robot's side turns the same
  // way as the base: a turn toward the wall (left for the camera's side, in travel terms)
  // goes round a convex corner of the solid (90 deg), a turn away from it round a concave
  // one (270 deg).
  corner_ = PendingCorner{odometer_in_, turn_rad, wall_range_in_, false, 0.0};
}

// Where the walls end and begin at a corner. The base turns in place at odometer reading
// c, with its centre r1 from the wall before and r2 from the wall after (coaxial sonar,
// read before and after the turn). Turning away from the wall (a concave corner, 270):
// the wall before runs on past the optical axis to the wall ahead, r2 further, and the
// wall after began r1 behind the axis's new foot. Turning toward the wall (convex, 90):
// the wall before ended r2 behind the axis — the base drove on into the crossing — and
// the wall after begins r1 ahead. A base on the mitred axis of a corner has r1 = r2 =
// half the hallway; a follower that turns early or late shifts them, which the ranges
// measure.
void EdgeAssembler::PlaceCorner(double range_after_in, std::vector<map::SensedEdge>& out) {
  const PendingCorner c = *corner_;
  corner_.reset();
  double r1 = c.range_before_in, r2 = range_after_in;
  if (!std::isfinite(r1)) r1 = r2;
  if (!std::isfinite(r2)) r2 = r1;
  if (!std::isfinite(r1)) r1 = r2 = 0.0;  // no range either side: the turn point itself
  const bool toward_wall = direction_ * c.turn_rad > 0.0;
  const double sign = toward_wall ? -1.0 : +1.0;
  EmitWallUpTo(c.odometer_in + sign * direction_ * r2, out);
  last_door_end_in_.reset();  // a corner lies between this door and the next
  pending_angle_deg_ = toward_wall ? 90.0 : 270.0;
  last_jamb_in_ = c.odometer_in - sign * direction_ * r1;
}

EdgeAssembler::Track* EdgeAssembler::NextLeaf(const Track& t, map::DoorClass* door_class) {
  for (Track& n : open_) {
    if (std::abs(Near(n) - Far(t)) >= config_.leaf_gap_in ||
        std::max(t.width(), n.width()) > config_.max_leaf_in ||
        std::abs(t.width() - n.width()) > config_.leaf_mismatch_in ||
        t.frames + n.frames < config_.min_frames) {
      continue;
    }
    if (const auto cls = DoubleDoorClass(direction_ * (Far(n) - Near(t)))) {
      *door_class = *cls;
      return &n;
    }
  }
  return nullptr;
}

bool EdgeAssembler::Decide(Track& t) {
  // A track seen in fewer frames is spurious, unless it is a leaf of a double door with the
  // other leaf beside it (the second leaf carries the double door by then): two alike leaves
  // sharing a stile and spanning a double door are seldom chance, and from the hallway axis a
  // leaf is often paired in one frame only.
  map::DoorClass double_class{};
  if (t.frames < config_.min_frames && !t.double_class && !NextLeaf(t, &double_class)) {
    return false;
  }
  const auto overlap = [](const Track& a, const Track& b) {
    return std::min(a.hi(), b.hi()) - std::max(a.lo(), b.lo());
  };
  // Pairs that overlap this one are the same landmark: the best supported is the door.
  for (const Track& o : open_) {
    if (o.frames >= config_.min_frames && overlap(t, o) > config_.max_overlap_in &&
        o.support > t.support) {
      return false;
    }
  }
  open_.erase(std::remove_if(open_.begin(), open_.end(),
                             [&](const Track& o) { return overlap(t, o) > config_.max_overlap_in; }),
              open_.end());
  if (t.double_class) return true;  // the second leaf of a double door
  // A wall panel between two doors, framed by their casings, looks like a door to the
  // detector. A "door" whose jambs both touch doors — the last one emitted and one already
  // in view — is that panel: leave it out, and the wall between the two real doors is
  // measured jamb to jamb as usual.
  const bool touches_previous =
      last_door_end_in_ && std::abs(Near(t) - *last_door_end_in_) < config_.min_wall_in;
  if (touches_previous && TouchesOneInView(t)) return false;
  // The first leaf of a double door: the next leaf starts at this one's far jamb (the
  // meeting stile) and is in view already; hand the double door over to it.
  if (Track* n = NextLeaf(t, &double_class)) {
    n->double_class = double_class;
    n->double_near_jamb_in = Near(t);
    // Both leaves carry the door's mark: their reads are one vote.
    for (int m = 0; m < map::kDoorMarkCount; ++m) n->mark_weight[m] += t.mark_weight[m];
    return false;
  }
  return true;
}

bool EdgeAssembler::TouchesOneInView(const Track& t) const {
  return std::any_of(open_.begin(), open_.end(), [&](const Track& n) {
    return std::abs(Near(n) - Far(t)) < config_.min_wall_in;
  });
}

void EdgeAssembler::Complete(Track t, std::vector<map::SensedEdge>& out) {
  const bool door = Decide(t);
  if (held_) {
    const Track h = *held_;
    held_.reset();
    // A row goes on past t: of h and t one is a door and the other the wall panel between
    // it and the next door. The door is the better supported of the two (the detector pairs
    // a door's jambs in more frames than the casings around a panel); a tie keeps h.
    const bool row =
        door && std::abs(Near(t) - Far(h)) < config_.min_wall_in && TouchesOneInView(t);
    if (row && t.support > h.support) {
      Emit(t, out);  // h was the panel: t begins the row, and the rule below keeps its phase
      return;
    }
    Emit(h, out);
    if (!door) return;
    if (row) return;  // t is the panel between h and the next door
  } else if (!door) {
    return;
  }
  // A door that does not follow one but touches one in view begins a row of doors and the
  // wall panels between them (each framed by two casings, a "door" to the detector), or is
  // that row's first panel: it waits for the track after it to say which (above).
  const bool follows_door =
      last_door_end_in_ && std::abs(Near(t) - *last_door_end_in_) < config_.min_wall_in;
  if (!follows_door && TouchesOneInView(t)) {
    held_ = t;
    return;
  }
  Emit(t, out);
}

std::optional<map::DoorClass> EdgeAssembler::DoubleDoorClass(double span_in) const {
  const double d30 = std::abs(span_in - 60.0), d36 = std::abs(span_in - 72.0);
  if (std::min(d30, d36) > config_.double_door_tolerance_in) return std::nullopt;
  return d30 < d36 ? map::DoorClass::k30_30 : map::DoorClass::k36_36;
}

map::DoorClass EdgeAssembler::Track::VotedClass() const {
  return static_cast<map::DoorClass>(
      std::max_element(std::begin(class_weight), std::end(class_weight)) - std::begin(class_weight));
}

map::DoorMark EdgeAssembler::Track::VotedMark() const {
  int best = static_cast<int>(map::DoorMark::kUnknown);
  for (int m = best + 1; m < map::kDoorMarkCount; ++m) {
    if (mark_weight[m] > 0.0 && (best == 0 || mark_weight[m] > mark_weight[best])) best = m;
  }
  return static_cast<map::DoorMark>(best);
}

void EdgeAssembler::Emit(const Track& t, std::vector<map::SensedEdge>& out) {
  if (t.double_class) {
    EmitEdges(t.double_near_jamb_in, Far(t), *t.double_class, t.VotedMark(), out);
    return;
  }
  EmitEdges(Near(t), Far(t), t.VotedClass(), t.VotedMark(), out);
}

void EdgeAssembler::EmitWallUpTo(double end_in, std::vector<map::SensedEdge>& out) {
  // From the previous door's far jamb (or corner), or from where the sequence began: then
  // only a lower bound, as the robot started inside it.
  const double wall_from = last_jamb_in_ ? *last_jamb_in_ : start_in_;
  const double wall_in = direction_ * (end_in - wall_from);
  if (wall_in < config_.min_wall_in) return;
  map::SensedEdge wall;
  wall.code = map::kWallCode;
  wall.metric_in = wall_in;
  wall.metric_is_lower_bound = !last_jamb_in_.has_value();
  wall.angle_deg = pending_angle_deg_;
  pending_angle_deg_ = std::numeric_limits<double>::quiet_NaN();
  out.push_back(wall);
  sequence_.push_back(wall);
  spans_.push_back({wall_from, end_in});
}

void EdgeAssembler::EmitEdges(double near_jamb_in, double far_jamb_in, map::DoorClass door_class,
                              map::DoorMark mark, std::vector<map::SensedEdge>& out) {
  EmitWallUpTo(near_jamb_in, out);
  map::SensedEdge door;
  door.angle_deg = pending_angle_deg_;
  pending_angle_deg_ = std::numeric_limits<double>::quiet_NaN();
  door.code = map::DoorCode(door_class);
  door.mark = mark;
  door.metric_in = direction_ * (far_jamb_in - near_jamb_in);
  out.push_back(door);
  sequence_.push_back(door);
  spans_.push_back({near_jamb_in, far_jamb_in});
  last_jamb_in_ = far_jamb_in;
  last_door_end_in_ = far_jamb_in;
}

}  // namespace stickrep::localizer
