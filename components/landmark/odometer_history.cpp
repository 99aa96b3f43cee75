#include "landmark/odometer_history.h"

#include <algorithm>

namespace stickrep::landmark {

bool OdometerHistory::Add(std::int64_t stamp_ns, double odometer_in) {
  if (!readings_.empty() && stamp_ns < readings_.back().stamp_ns) return false;
  readings_.push_back({stamp_ns, odometer_in});
  if (readings_.size() > capacity_) readings_.pop_front();
  return true;
}

std::optional<double> OdometerHistory::At(std::int64_t stamp_ns,
                                          std::int64_t max_extrapolation_ns) const {
  if (readings_.empty()) return std::nullopt;
  if (stamp_ns <= readings_.front().stamp_ns) {
    if (readings_.front().stamp_ns - stamp_ns > max_extrapolation_ns) return std::nullopt;
    return readings_.front().odometer_in;
  }
  if (stamp_ns >= readings_.back().stamp_ns) {
    const Reading& last = readings_.back();
    if (stamp_ns - last.stamp_ns > max_extrapolation_ns) return std::nullopt;
    if (readings_.size() < 2) return last.odometer_in;
    // A frame may arrive before the odometry of its own instant: carry the latest speed on.
    const Reading& prev = readings_[readings_.size() - 2];
    const double span = static_cast<double>(last.stamp_ns - prev.stamp_ns);
    if (span <= 0.0) return last.odometer_in;
    const double speed = (last.odometer_in - prev.odometer_in) / span;
    return last.odometer_in + speed * static_cast<double>(stamp_ns - last.stamp_ns);
  }
  const auto after = std::lower_bound(
      readings_.begin(), readings_.end(), stamp_ns,
      [](const Reading& r, std::int64_t t) { return r.stamp_ns < t; });
  const auto before = after - 1;
  const double span = static_cast<double>(after->stamp_ns - before->stamp_ns);
  const double w = span > 0 ? (stamp_ns - before->stamp_ns) / span : 0.0;
  return before->odometer_in + w * (after->odometer_in - before->odometer_in);
}

}  // namespace stickrep::landmark
