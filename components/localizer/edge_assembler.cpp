#include "localizer/edge_assembler.h"

#include <algorithm>
#include <cmath>

namespace stickrep::localizer {

void EdgeAssembler::AddSighting(const DoorSighting& s) {
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
  sequence_.clear();
  last_jamb_in_.reset();
  start_in_ = odometer_in_;
}

std::vector<map::SensedEdge> EdgeAssembler::Advance(double odometer_in) {
  std::vector<map::SensedEdge> out;
  if (!have_odometer_) {
    have_odometer_ = true;
    start_in_ = odometer_in;
  }
  if (std::abs(odometer_in - odometer_in_) > 1e-6 && direction_ == 0) {
    direction_ = odometer_in > start_in_ ? +1 : -1;
  }
  odometer_in_ = odometer_in;
  if (direction_ == 0) return out;
  // Complete the tracks the optical axis has left behind, nearest first.
  std::sort(open_.begin(), open_.end(), [this](const Track& a, const Track& b) {
    return direction_ * a.along() < direction_ * b.along();
  });
  while (!open_.empty() &&
         direction_ * (odometer_in_ - open_.front().along()) > config_.out_of_view_in) {
    const Track t = open_.front();
    open_.erase(open_.begin());
    if (t.frames >= config_.min_frames) Emit(t, out);
  }
  return out;
}

void EdgeAssembler::Emit(const Track& t, std::vector<map::SensedEdge>& out) {
  const int best = static_cast<int>(std::max_element(std::begin(t.class_weight),
                                                     std::end(t.class_weight)) -
                                    std::begin(t.class_weight));
  std::vector<double> widths = t.widths;
  std::nth_element(widths.begin(), widths.begin() + widths.size() / 2, widths.end());
  const double width = widths[widths.size() / 2];
  const double near_jamb = t.along() - direction_ * width / 2.0;
  const double far_jamb = t.along() + direction_ * width / 2.0;
  // The wall before this door: from the previous door's far jamb, or from where the
  // sequence began (then only a lower bound: the robot started inside it).
  const double wall_from = last_jamb_in_ ? *last_jamb_in_ : start_in_;
  const double wall_in = direction_ * (near_jamb - wall_from);
  if (wall_in >= config_.min_wall_in) {
    map::SensedEdge wall;
    wall.code = map::kWallCode;
    wall.metric_in = wall_in;
    wall.metric_is_lower_bound = !last_jamb_in_.has_value();
    out.push_back(wall);
    sequence_.push_back(wall);
  }
  map::SensedEdge door;
  door.code = map::DoorCode(static_cast<map::DoorClass>(best));
  door.metric_in = width;
  out.push_back(door);
  sequence_.push_back(door);
  last_jamb_in_ = far_jamb;
}

}  // namespace stickrep::localizer
