#include "virtual_robot/hallway_sim.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/units.h"

namespace stickrep::virtual_robot {

HallwaySim::HallwaySim(const map::Map& map, const SimWorldConfig& world,
                       const SimRobotConfig& robot, double start_x_in, uint64_t seed)
    : world_(world), robot_(robot), rng_(seed) {
  if (map.RingCount() == 0) throw std::invalid_argument("the map has no rings");
  const int r = world.ring_id.empty() ? 0 : map.FindRing(world.ring_id);
  if (r < 0) throw std::invalid_argument("no ring '" + world.ring_id + "' in the map");
  const map::Ring& ring = map.ring(r);
  ring_id_ = ring.id;
  closed_ = ring.closed;
  double x = 0.0;
  for (const map::Edge& e : ring.edges) {
    edge_start_in_.push_back(x);
    is_door_.push_back(e.IsDoor());
    is_double_.push_back(e.IsDoor() && map::IsDoubleDoor(*e.door_class));
    x += e.metric_in;
  }
  edge_start_in_.push_back(x);
  length_in_ = x;
  x_in_ = WrapX(start_x_in);
}

double HallwaySim::WrapX(double x) const {
  if (!closed_) return std::clamp(x, 0.0, length_in_);
  x = std::fmod(x, length_in_);
  return x < 0.0 ? x + length_in_ : x;
}

void HallwaySim::Step(double dt_s, double left_ftps, double right_ftps) {
  const double vmax = robot_.max_speed_ftps;
  const double dl = FeetToInches(std::clamp(left_ftps, -vmax, vmax)) * dt_s;
  const double dr = FeetToInches(std::clamp(right_ftps, -vmax, vmax)) * dt_s;
  left_travel_in_ += dl;
  right_travel_in_ += dr;
  const double ds = 0.5 * (dl + dr);
  const double dtheta = (dr - dl) / robot_.wheel_base_in;
  const double mid = heading_rad_ + 0.5 * dtheta;
  x_in_ = WrapX(x_in_ + ds * std::cos(mid));
  // Stay between the walls: the hallway is the robot's whole world.
  const double half = 0.5 * world_.hallway_width_in - robot_.head_radius_in;
  y_in_ = std::clamp(y_in_ + ds * std::sin(mid), -half, half);
  heading_rad_ = std::remainder(heading_rad_ + dtheta, 2.0 * kPi);
  distance_in_ += std::abs(ds);
}

double HallwaySim::RayRange(double bearing_rad) const {
  // Walls at y = +W/2 (mapped) and y = -W/2, infinite along x; no end walls.
  const double s = std::sin(bearing_rad);
  if (std::abs(s) < 1e-9) return 0.0;
  const double wall_y = s > 0.0 ? 0.5 * world_.hallway_width_in : -0.5 * world_.hallway_width_in;
  return (wall_y - y_in_) / s;
}

SonarRanges HallwaySim::Sonar() const {
  SonarRanges ranges{};
  for (int k = 0; k < robot_.sonar_count && k < static_cast<int>(ranges.size()); ++k) {
    // The optical axis looks at the mapped wall (+90 deg); sensor k sits k steps toward the
    // image's right, which is the base's forward direction.
    const double bearing = heading_rad_ + kPi / 2.0 -
                           DegToRad(robot_.sonar_spacing_deg) * (k - robot_.coaxial_sensor);
    const double r = RayRange(bearing) - robot_.head_radius_in;
    ranges[k] = (r > 0.0 && r <= robot_.sonar_max_range_in) ? static_cast<float>(r) : 0.0f;
  }
  return ranges;
}

std::vector<uint8_t> HallwaySim::RenderFrame() {
  const int w = robot_.image_width_px, h = robot_.image_height_px;
  std::vector<uint8_t> img(static_cast<size_t>(w) * h);
  const double f = 0.5 * w / std::tan(DegToRad(robot_.fov_deg) / 2.0);
  const double d = 0.5 * world_.hallway_width_in - y_in_;  // camera to the mapped wall
  const double cx = 0.5 * w, cy = 0.5 * h;
  // Row of a height on the wall; column of a position along the wall.
  auto row_of = [&](double z) { return cy - f * (z - robot_.camera_height_in) / d; };
  const double floor_row = row_of(0.0), ceiling_row = row_of(world_.ceiling_height_in);
  const double door_top_row = row_of(world_.door_height_in);
  std::vector<uint8_t> column_shade(w, 170);   // plain wall
  std::vector<bool> column_is_door(w, false);
  for (int u = 0; u < w; ++u) {
    const double x = WrapX(x_in_ + (u + 0.5 - cx) * d / f);
    const auto it = std::upper_bound(edge_start_in_.begin(), edge_start_in_.end(), x);
    const int e = std::clamp(static_cast<int>(it - edge_start_in_.begin()) - 1, 0,
                             static_cast<int>(is_door_.size()) - 1);
    const int n = static_cast<int>(is_door_.size());
    if (is_door_[e]) {
      column_is_door[u] = true;
      column_shade[u] = 110;  // the leaf between the jambs: the edge's metric is its width
      const double mid = 0.5 * (edge_start_in_[e] + edge_start_in_[e + 1]);
      if (is_double_[e] && std::abs(x - mid) < 0.5 * world_.jamb_width_in) column_shade[u] = 50;
      continue;
    }
    // The jambs frame a door from outside its opening, so they lie on the wall edges next
    // to it (wrapping around a closed ring).
    const bool door_before = closed_ || e > 0 ? is_door_[(e + n - 1) % n] : false;
    const bool door_after = closed_ || e + 1 < n ? is_door_[(e + 1) % n] : false;
    if ((door_before && x - edge_start_in_[e] < world_.jamb_width_in) ||
        (door_after && edge_start_in_[e + 1] - x < world_.jamb_width_in)) {
      column_is_door[u] = true;
      column_shade[u] = 50;
    }
  }
  std::normal_distribution<double> noise(0.0, world_.image_noise_sigma);
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      double shade;
      if (v > floor_row) {
        shade = 80;
      } else if (v < ceiling_row) {
        shade = 215;
      } else if (column_is_door[u] && v > door_top_row) {
        shade = column_shade[u];
      } else {
        shade = 170;
      }
      img[static_cast<size_t>(v) * w + u] =
          static_cast<uint8_t>(std::clamp(shade + noise(rng_), 0.0, 255.0));
    }
  }
  return img;
}

SimTruth HallwaySim::Truth() const {
  SimTruth t;
  t.x_in = x_in_;
  t.y_in = y_in_;
  t.heading_rad = heading_rad_;
  const auto it = std::upper_bound(edge_start_in_.begin(), edge_start_in_.end(), x_in_);
  t.edge_index = std::clamp(static_cast<int>(it - edge_start_in_.begin()) - 1, 0,
                            static_cast<int>(is_door_.size()) - 1);
  t.offset_in = x_in_ - edge_start_in_[t.edge_index];
  t.distance_in = distance_in_;
  return t;
}

}  // namespace stickrep::virtual_robot
