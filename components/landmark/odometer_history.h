#pragma once

#include <cstdint>
#include <deque>
#include <optional>

namespace stickrep::landmark {

// Recent odometer readings by time, so that a frame can be placed at the odometer reading
// of the instant it was taken rather than of the latest odometry sample (at 2.6 ft/s a
// 50 ms difference is 1.6 in).
class OdometerHistory {
 public:
  explicit OdometerHistory(std::size_t capacity = 200) : capacity_(capacity) {}
  // Readings must come in time order; an older one is ignored and false returned.
  bool Add(std::int64_t stamp_ns, double odometer_in);
  // Linear interpolation at `stamp_ns`; past the newest reading (a frame that arrives
  // before the odometry of its instant) the last speed is carried on, before the oldest the
  // oldest reading is used, each within `max_extrapolation_ns`; empty if none is close.
  std::optional<double> At(std::int64_t stamp_ns, std::int64_t max_extrapolation_ns) const;

 private:
  struct Reading {
    std::int64_t stamp_ns;
    double odometer_in;
  };
  std::size_t capacity_;
  std::deque<Reading> readings_;
};

}  // namespace stickrep::landmark
