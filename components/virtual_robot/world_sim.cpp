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

  world::MapWorldOptions options;
  options.hallway_width_in = config.hallway_width_in;
  options.opposite_wall = world::OppositeWall::kAlways;
  options.open_door_fraction = config.open_door_fraction;
  std::mt19937_64 world_rng(seed ^ 0x9E3779B97F4A7C15ull);
  scene_ = std::make_unique<world::Scene>(world::BuildRingWorld(map, ring_, options, world_rng).world);
  camera_ = std::make_unique<world::CameraRenderer>(models_.camera);
  models_.base.slip_stddev = config.wheel_slip_stddev;
  position_in_ = Wrap(start_offset_in);
}

double WorldSim::Wrap(double s) const {
  if (!closed_) return std::clamp(s, 0.0, length_in_);
  s = std::fmod(s, length_in_);
  return s < 0.0 ? s + length_in_ : s;
}

int WorldSim::EdgeAt(double s) const {
  const auto it = std::upper_bound(edge_start_in_.begin(), edge_start_in_.end(), s);
  return std::clamp(static_cast<int>(it - edge_start_in_.begin()) - 1, 0, edge_count() - 1);
}

world::Pose2d WorldSim::PoseAt(double s) const {
  const int e = EdgeAt(s);
  const Eigen::Vector2d a = node_in_[e], b = node_in_[e + 1];
  const double seg = (b - a).norm();
  const Eigen::Vector2d u = seg > 0.0 ? Eigen::Vector2d((b - a) / seg) : Eigen::Vector2d(1, 0);
  const double metric = edge_start_in_[e + 1] - edge_start_in_[e];
  // The map's node spacing may differ from the metric by up to 1 % (map_io.h).
  const Eigen::Vector2d foot = a + u * ((s - edge_start_in_[e]) * seg / metric);
  const Eigen::Vector2d left(-u.y(), u.x());  // the hallway lies left of ring order
  const Eigen::Vector2d p = foot + left * (0.5 * config_.hallway_width_in);
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

void WorldSim::Teleport(double ring_position_in) { position_in_ = Wrap(ring_position_in); }

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
  t.edge_index = EdgeAt(position_in_);
  t.offset_in = position_in_ - edge_start_in_[t.edge_index];
  t.distance_in = distance_in_;
  t.forward_in_ring = travel_sign_ < 0;
  return t;
}

}  // namespace stickrep::virtual_robot
