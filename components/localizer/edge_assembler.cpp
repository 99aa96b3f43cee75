#include "localizer/edge_assembler.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stickrep::localizer {

void EdgeAssembler::AddSighting(const DoorSighting& s) {
  // While the base turns in place the camera sweeps across the corner: no wall is square
  // to it and a sighting has no place along either wall.
  if (corner_ && !corner_->settled) return;
  for (Track& t : open_) {
    if (std::abs(t.along() - s.along_in) < config_.same_door_in) {
      t.along_sum += s.along_in;
      t.frames++;
      t.class_weight[static_cast<int>(s.door_class)] += std::max(s.confidence, 1e-3);
      t.widths.push_back(s.width_in);
      return;
    }
  }
  Track t;
  t.along_sum = s.along_in;
  t.frames = 1;
  t.class_weight[static_cast<int>(s.door_class)] = std::max(s.confidence, 1e-3);
  t.widths.push_back(s.width_in);
  open_.push_back(std::move(t));
}

void EdgeAssembler::Restart() {
  open_.clear();
  corner_.reset();
  placed_.clear();
  sequence_.clear();
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
  }
  odometer_in_ = odometer_in;
  if (direction_ == 0) return out;
  out.swap(placed_);
  if (corner_) {
    if (!corner_->settled) {
      const double off = std::remainder(heading_rad - *heading_ref_rad_, 2.0 * M_PI);
      if (std::abs(off) * 180.0 / M_PI < config_.turn_settled_deg) {
        corner_->settled = true;
        corner_->settled_odometer_in = odometer_in_;
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
    if (t.frames < config_.min_frames) continue;
    // A leaf of a double door: the next door starts right at this one's far jamb. That
    // door is in view already (its centre is nearer than this one's by about a leaf), so
    // it is an open track now; hand this leaf over to it.
    const map::DoorClass leaf = t.VotedClass();
    const double far_jamb = t.along() + direction_ * t.MedianWidth() / 2.0;
    // A wall panel between two doors, framed by their casings, looks like a door to the
    // detector (Figure 4.1 pairs any two strong vertical edges). A "door" whose jambs both
    // touch doors — the last one emitted and one already in view — is that panel: leave it
    // out, and the wall between the two real doors is measured jamb to jamb as usual.
    const double near_jamb = t.along() - direction_ * t.MedianWidth() / 2.0;
    const bool touches_previous =
        last_door_end_in_ && std::abs(near_jamb - *last_door_end_in_) < config_.min_wall_in;
    const bool touches_next =
        std::any_of(open_.begin(), open_.end(), [&](const Track& n) {
          const double n_near = n.along() - direction_ * n.MedianWidth() / 2.0;
          return n.frames >= config_.min_frames &&
                 std::abs(n_near - far_jamb) < config_.min_wall_in;
        });
    if (!t.first_leaf && touches_previous && touches_next) continue;
    if (!t.first_leaf && (leaf == map::DoorClass::k30 || leaf == map::DoorClass::k36)) {
      auto next = std::find_if(open_.begin(), open_.end(), [&](const Track& n) {
        const double near = n.along() - direction_ * n.MedianWidth() / 2.0;
        return n.VotedClass() == leaf && std::abs(near - far_jamb) < config_.min_wall_in;
      });
      if (next != open_.end()) {
        next->first_leaf = leaf;
        next->first_leaf_near_jamb_in = t.along() - direction_ * t.MedianWidth() / 2.0;
        continue;
      }
    }
    Emit(t, out);
  }
  if (!heading_ref_rad_) heading_ref_rad_ = heading_rad;
  const double turn = std::remainder(heading_rad - *heading_ref_rad_, 2.0 * M_PI);
  if (std::abs(turn) * 180.0 / M_PI < config_.turn_settled_deg) {
    if (std::isfinite(unconfirmed_range_in_)) wall_range_in_ = unconfirmed_range_in_;
  }
  unconfirmed_range_in_ = std::numeric_limits<double>::quiet_NaN();
  if (std::abs(turn) * 180.0 / M_PI > config_.corner_turn_deg) {
    // The reference turns by whole quarter turns: the hallway's corners are square (A3).
    const double quarter = std::round(turn / (M_PI / 2.0)) * (M_PI / 2.0);
    BeginCorner(quarter, out);
    heading_ref_rad_ = std::remainder(*heading_ref_rad_ + quarter, 2.0 * M_PI);
  }
  return out;
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
    const Track t = open_.front();
    open_.erase(open_.begin());
    if (t.frames >= config_.min_frames) Emit(t, out);
  }
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

map::DoorClass EdgeAssembler::Track::VotedClass() const {
  return static_cast<map::DoorClass>(
      std::max_element(std::begin(class_weight), std::end(class_weight)) - std::begin(class_weight));
}

double EdgeAssembler::Track::MedianWidth() const {
  std::vector<double> w = widths;
  std::nth_element(w.begin(), w.begin() + w.size() / 2, w.end());
  return w[w.size() / 2];
}

void EdgeAssembler::Emit(const Track& t, std::vector<map::SensedEdge>& out) {
  const double width = t.MedianWidth();
  const double far_jamb = t.along() + direction_ * width / 2.0;
  if (t.first_leaf && *t.first_leaf == t.VotedClass()) {
    const map::DoorClass double_class =
        *t.first_leaf == map::DoorClass::k30 ? map::DoorClass::k30_30 : map::DoorClass::k36_36;
    EmitEdges(t.first_leaf_near_jamb_in, far_jamb, double_class, out);
    return;
  }
  EmitEdges(t.along() - direction_ * width / 2.0, far_jamb, t.VotedClass(), out);
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
}

void EdgeAssembler::EmitEdges(double near_jamb_in, double far_jamb_in, map::DoorClass door_class,
                              std::vector<map::SensedEdge>& out) {
  EmitWallUpTo(near_jamb_in, out);
  map::SensedEdge door;
  door.angle_deg = pending_angle_deg_;
  pending_angle_deg_ = std::numeric_limits<double>::quiet_NaN();
  door.code = map::DoorCode(door_class);
  door.metric_in = direction_ * (far_jamb_in - near_jamb_in);
  out.push_back(door);
  sequence_.push_back(door);
  last_jamb_in_ = far_jamb_in;
  last_door_end_in_ = far_jamb_in;
}

}  // namespace stickrep::localizer
