#include "virtual_robot/world_sim.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/units.h"

namespace stickrep::virtual_robot {

WorldSim::WorldSim(const map::Map& map, const sensing::RobotConfig& robot,
                   const WorldSimConfig& config, double start_offset_in, std::uint64_t seed)
    : config_(config),
      models_(world::RobotModelsFromConfig(robot)),
      sonar_(models_.sonar),
      rng_(seed) {
  if (map.RingCount() == 0) throw std::invalid_argument("the map has no rings");
  ring_ = config.ring_id.empty() ? 0 : map.FindRing(config.ring_id);
  if (ring_ < 0) throw std::invalid_argument("no ring '" + config.ring_id + "' in the map");
  const map::Ring& ring = map.ring(ring_);
  ring_id_ = ring.id;
  closed_ = ring.closed;
  double s = 0.0;
  for (int i = 0; i < ring.EdgeCount(); ++i) {
    node_in_.emplace_back(ring.nodes[i].x_in, ring.nodes[i].y_in);
    edge_start_in_.push_back(s);
    s += ring.edges[i].metric_in;
  }
  const map::Node& last = ring.nodes[closed_ ? 0 : ring.EdgeCount()];
  node_in_.emplace_back(last.x_in, last.y_in);
  edge_start_in_.push_back(s);
  length_in_ = s;
  BuildAxis();

  world::MapWorldOptions options;
  options.hallway_width_in = config.hallway_width_in;
  options.opposite_wall = world::OppositeWall::kAlways;
  options.open_door_fraction = config.open_door_fraction;
  std::mt19937_64 world_rng(seed ^ 0x9E3779B97F4A7C15ull);
  scene_ = std::make_unique<world::Scene>(world::BuildRingWorld(map, ring_, options, world_rng).world);
  camera_ = std::make_unique<world::CameraRenderer>(models_.camera);
  models_.base.slip_stddev = config.wheel_slip_stddev;
  position_in_ = PathFromRing(start_offset_in);
}

double WorldSim::Wrap(double p) const {
  const double total = axis_start_in_.back();
  if (!closed_) return std::clamp(p, 0.0, total);
  p = std::fmod(p, total);
  return p < 0.0 ? p + total : p;
}

int WorldSim::SegmentAt(double p) const {
  const auto it = std::upper_bound(axis_start_in_.begin(), axis_start_in_.end(), p);
  return std::clamp(static_cast<int>(it - axis_start_in_.begin()) - 1, 0, edge_count() - 1);
}

double WorldSim::PathFromRing(double s) const {
  if (closed_) {
    s = std::fmod(s, length_in_);
    if (s < 0.0) s += length_in_;
  }
  s = std::clamp(s, 0.0, length_in_);
  const auto it = std::upper_bound(edge_start_in_.begin(), edge_start_in_.end(), s);
  const int e = std::clamp(static_cast<int>(it - edge_start_in_.begin()) - 1, 0, edge_count() - 1);
  const double metric = edge_start_in_[e + 1] - edge_start_in_[e];
  const double f = metric > 0.0 ? (s - edge_start_in_[e]) / metric : 0.0;
  return axis_start_in_[e] + f * (axis_start_in_[e + 1] - axis_start_in_[e]);
}

double WorldSim::RingPosition() const {
  const SimTruth t = Truth();
  return edge_start_in_[t.edge_index] + t.offset_in;
}

namespace {

Eigen::Vector2d Unit(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = b - a;
  return d.norm() > 0.0 ? Eigen::Vector2d(d / d.norm()) : Eigen::Vector2d(1.0, 0.0);
}

Eigen::Vector2d Left(const Eigen::Vector2d& u) { return {-u.y(), u.x()}; }

}  // namespace

void WorldSim::BuildAxis() {
  const double h = 0.5 * config_.hallway_width_in;
  const int n = edge_count();
  axis_in_.resize(n + 1);
  for (int i = 0; i <= n; ++i) {
    const bool has_before = closed_ || i > 0;
    const bool has_after = closed_ || i < n;
    const int before = (i - 1 + n) % n, after = i % n;
    const Eigen::Vector2d node = node_in_[i];
    if (!has_before || !has_after) {
      const int e = has_after ? after : before;
      axis_in_[i] = node + Left(Unit(node_in_[e], node_in_[e + 1])) * h;
      continue;
    }
    const Eigen::Vector2d ua = Unit(node_in_[before], node_in_[before + 1]);
    const Eigen::Vector2d ub = Unit(node_in_[after], node_in_[after + 1]);
    const Eigen::Vector2d na = Left(ua), nb = Left(ub);
    const double cross = ua.x() * ub.y() - ua.y() * ub.x();
    Eigen::Vector2d m = node + na * h;
    if (std::abs(cross) > 1e-6) {
      // node + na h + ua t = node + nb h + ub u: the two offset lines meet at the mitre.
      const Eigen::Vector2d rhs = (nb - na) * h;
      const double t = (rhs.x() * ub.y() - rhs.y() * ub.x()) / cross;
      m = node + na * h + ua * t;
      // A jog shorter than the hallway is wide would throw the mitre far off: keep the
      // axis near the node there.
      if ((m - node).norm() > 3.0 * h) m = node + (na + nb).normalized() * h;
    }
    axis_in_[i] = m;
  }
  // Path length along the axis; a mitred segment that folds back (a jog narrower than the
  // hallway) has no length of its own.
  axis_start_in_.assign(n + 1, 0.0);
  for (int e = 0; e < n; ++e) {
    const Eigen::Vector2d u = Unit(node_in_[e], node_in_[e + 1]);
    axis_start_in_[e + 1] = axis_start_in_[e] + std::max(0.0, (axis_in_[e + 1] - axis_in_[e]).dot(u));
  }
}

world::Pose2d WorldSim::PoseAt(double path_in) const {
  const int e = SegmentAt(path_in);
  const Eigen::Vector2d u = Unit(node_in_[e], node_in_[e + 1]);
  const Eigen::Vector2d p = axis_in_[e] + u * (path_in - axis_start_in_[e]);
  // Facing against ring order puts the wall on the base's left, where the camera looks.
  return world::Pose2d{p.x(), p.y(), std::atan2(-u.y(), -u.x())};
}

void WorldSim::Step(double dt_s, double left_ftps, double right_ftps) {
  const double vmax = models_.base.max_speed_ftps;
  const double dl = FeetToInches(std::clamp(left_ftps, -vmax, vmax)) * dt_s;
  const double dr = FeetToInches(std::clamp(right_ftps, -vmax, vmax)) * dt_s;
  left_travel_in_ += dl;
  right_travel_in_ += dr;
  std::normal_distribution<double> slip(0.0, models_.base.slip_stddev);
  const double ds = 0.5 * (dl * (1.0 + slip(rng_)) + dr * (1.0 + slip(rng_)));
  if (ds != 0.0) travel_sign_ = ds > 0.0 ? 1 : -1;
  // Forward travel of the base is against ring order.
  const double heading_before = PoseAt(position_in_).theta_rad;
  position_in_ = Wrap(position_in_ - ds);
  // At a corner the base turns in place to follow the hallway (A3); the encoders see the
  // turn as opposite wheel travel, so odometry turns with the robot.
  const double turn = std::remainder(PoseAt(position_in_).theta_rad - heading_before, 2 * kPi);
  if (std::abs(turn) > 1e-9) {
    left_travel_in_ -= turn * models_.base.wheel_base_in / 2.0;
    right_travel_in_ += turn * models_.base.wheel_base_in / 2.0;
  }
  distance_in_ += std::abs(ds);
}

void WorldSim::Teleport(double ring_position_in) { position_in_ = PathFromRing(ring_position_in); }

std::array<float, 24> WorldSim::Sonar() {
  std::array<float, 24> out{};
  const world::Pose2d X_WR = PoseAt(position_in_);
  const std::vector<world::SonarReading> readings =
      config_.sonar_surface_errors ? sonar_.Sense(*scene_, X_WR, sonar_errors_, rng_)
                                   : sonar_.SenseExact(*scene_, X_WR);
  for (size_t k = 0; k < readings.size() && k < out.size(); ++k) {
    out[k] = readings[k].valid ? static_cast<float>(readings[k].range_in) : 0.0f;
  }
  return out;
}

std::vector<std::uint8_t> WorldSim::RenderFrame() {
  world::Illumination light;
  light.noise_stddev = config_.image_noise_sigma;
  const world::RenderedFrame frame = camera_->Render(*scene_, PoseAt(position_in_), light, rng_);
  const cv::Mat img = frame.image.isContinuous() ? frame.image : frame.image.clone();
  return std::vector<std::uint8_t>(img.data, img.data + img.total());
}

SimTruth WorldSim::Truth() const {
  SimTruth t;
  t.X_WR = PoseAt(position_in_);
  t.ring = ring_;
  // The edge the camera looks at: the foot of the optical axis on the segment's wall.
  t.edge_index = SegmentAt(position_in_);
  const Eigen::Vector2d node = node_in_[t.edge_index];
  const Eigen::Vector2d u = Unit(node, node_in_[t.edge_index + 1]);
  const double metric = edge_start_in_[t.edge_index + 1] - edge_start_in_[t.edge_index];
  t.offset_in = std::clamp((t.X_WR.position() - node).dot(u), 0.0, metric);
  t.distance_in = distance_in_;
  t.forward_in_ring = travel_sign_ < 0;
  return t;
}

}  // namespace stickrep::virtual_robot
