#include "virtual_robot/world_sim.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/units.h"
#include "world/diff_drive.h"

namespace stickrep::virtual_robot {

namespace {

// Panels standing lower than this can stop the base (walls, frames, door leaves); door
// headers start above it. Not in the text: a LabMate with its sonar head is about 3 ft tall.
constexpr double kBaseHeightIn = 36.0;
// Steps of the wall shorter than this are passed straight: the axis and the opposite wall
// run past them (world::MapWorldOptions::opposite_wall_max_step_in).
constexpr double kMaxStepIn = 36.0;

Eigen::Vector2d Unit(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = b - a;
  return d.norm() > 0.0 ? Eigen::Vector2d(d / d.norm()) : Eigen::Vector2d(1.0, 0.0);
}

Eigen::Vector2d Left(const Eigen::Vector2d& u) { return {-u.y(), u.x()}; }

double WrapPi(double a) { return std::remainder(a, 2.0 * kPi); }

// Distance from p to the segment a-b, and the parameter of the foot (0 at a, 1 at b).
double SegmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                       const Eigen::Vector2d& b, double* t_out = nullptr) {
  const Eigen::Vector2d d = b - a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  if (t_out) *t_out = t;
  return (p - (a + t * d)).norm();
}

// Where the ray origin + t dir (t > 0) crosses the segment a-b, or a negative value.
double RaySegment(const Eigen::Vector2d& origin, const Eigen::Vector2d& dir,
                  const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d e = b - a;
  const double denom = dir.x() * e.y() - dir.y() * e.x();
  if (std::abs(denom) < 1e-12) return -1.0;
  const Eigen::Vector2d w = a - origin;
  const double t = (w.x() * e.y() - w.y() * e.x()) / denom;
  const double s = (w.x() * dir.y() - w.y() * dir.x()) / denom;
  if (t <= 1e-9 || s < 0.0 || s > 1.0) return -1.0;
  return t;
}

}  // namespace

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
  corridor_outline_ = ring.outline == map::Outline::kCorridor;
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
  BuildAxis(ring);
  const auto walls_of = [](const map::Ring& r) {
    RingWalls w{r.id, {}, {}};
    for (int i = 0; i <= r.EdgeCount(); ++i) {
      const map::Node& n = r.nodes[i == r.EdgeCount() && r.closed ? 0 : i];
      w.node_in.emplace_back(n.x_in, n.y_in);
    }
    for (const map::Edge& e : r.edges) w.metric_in.push_back(e.metric_in);
    return w;
  };
  walls_.push_back(walls_of(ring));
  if (ring.outline == map::Outline::kCorridor) {
    for (int r = 0; r < map.RingCount(); ++r) {
      if (r != ring_) walls_.push_back(walls_of(map.ring(r)));
    }
  }

  world::MapWorldOptions options;
  options.hallway_width_in = config.hallway_width_in;
  options.opposite_wall_max_step_in = kMaxStepIn;
  options.open_door_fraction = config.open_door_fraction;
  std::mt19937_64 world_rng(seed ^ 0x9E3779B97F4A7C15ull);
  world::World built;
  if (ring.outline == map::Outline::kCorridor) {
    // A corridor outline (map format 2) stands in its building: every ring of the floor is
    // built (columns, other corridors), and walls are added only opposite side rings whose
    // width the map gives.
    options.opposite_wall = world::OppositeWall::kAuto;
    built = world::BuildMapWorld(map, options, world_rng).world;
  } else {
    // A side ring on its own: the opposite wall at the ring's width, else the configured one.
    options.opposite_wall = world::OppositeWall::kAlways;
    built = world::BuildRingWorld(map, ring_, options, world_rng).world;
  }
  // Realism draws from a stream of its own, so switching it leaves the rest of the run's
  // draws (doors, slip, noise) as they were.
  std::mt19937_64 realism_rng(seed ^ 0xC2B2AE3D27D4EB4Full);
  world::ApplyRealism(config.realism, realism_rng, &built);
  scene_ = std::make_unique<world::Scene>(std::move(built));
  for (int i = 0; i < static_cast<int>(scene_->panels().size()); ++i) {
    const world::Panel& p = scene_->panels()[i];
    if (p.acoustic && p.bottom_in < kBaseHeightIn) obstacle_panels_.push_back(i);
  }
  camera_ = std::make_unique<world::CameraRenderer>(
      world::DrawCamera(config.realism, models_.camera, realism_rng));
  light_rng_.seed(seed ^ 0x165667B19E3779F9ull);
  models_.base.slip_stddev = config.wheel_slip_stddev;
  footprint_radius_in_ = robot.sonar_ring.head_radius_in;

  X_WR_ = AxisPoseAbreast(start_offset_in);
  const double a = X_WR_.theta_rad + kPi;  // the axis direction in ring order
  const Eigen::Vector2d toward_wall = -Left({std::cos(a), std::sin(a)});
  const Eigen::Vector2d p = X_WR_.position() + toward_wall * config.start_lateral_offset_in;
  X_WR_ = world::Pose2d{p.x(), p.y(),
                        WrapPi(X_WR_.theta_rad + DegToRad(config.start_heading_error_deg))};
  if (Clearance(X_WR_.position()) < footprint_radius_in_) {
    throw ImpossibleStart("the start pose (" + std::to_string(config.start_lateral_offset_in) +
                                " in off the hallway axis) puts the base against a wall");
  }
}

void WorldSim::BuildAxis(const map::Ring& ring) {
  // The axis the follower keeps to: midway between the mapped wall, its shallow steps passed
  // straight, and the opposite wall (built from the same runs, world::BuildRingWorld).
  const std::vector<world::WallRun> runs =
      world::WithoutSteps(world::SplitIntoWallRuns(ring), closed_, kMaxStepIn);
  hallway_width_in_ = ring.width_in.value_or(config_.hallway_width_in);
  axis_ = world::OffsetRuns(runs, closed_, 0.5 * hallway_width_in_);
  if (axis_.empty()) throw std::invalid_argument("ring '" + ring.id + "' has no hallway axis");
  axis_of_edge_.assign(edge_count(), -1);
  for (int j = 0; j < static_cast<int>(axis_.size()); ++j) {
    const world::WallRun& run = runs[axis_[j].run];
    for (int e = run.first;; e = (e + 1) % edge_count()) {
      axis_of_edge_[e] = j;
      if (e == run.last) break;
    }
  }
  axis_start_in_.assign(1, 0.0);
  for (const world::OffsetSegment& seg : axis_) {
    axis_start_in_.push_back(axis_start_in_.back() + (seg.b_in - seg.a_in).norm());
  }
}

world::Pose2d WorldSim::AxisPoseAbreast(double s) const {
  if (closed_) {
    s = std::fmod(s, length_in_);
    if (s < 0.0) s += length_in_;
  }
  s = std::clamp(s, 0.0, length_in_);
  const auto it = std::upper_bound(edge_start_in_.begin(), edge_start_in_.end(), s);
  const int e = std::clamp(static_cast<int>(it - edge_start_in_.begin()) - 1, 0, edge_count() - 1);
  const double metric = edge_start_in_[e + 1] - edge_start_in_[e];
  const double f = metric > 0.0 ? (s - edge_start_in_[e]) / metric : 0.0;
  const Eigen::Vector2d on_wall = node_in_[e] + f * (node_in_[e + 1] - node_in_[e]);
  // The axis segment of the edge's run. An edge whose run collapsed (a jog narrower than
  // the hallway) or left only a stub of axis shorter than the hallway is wide (the back or
  // a side of an alcove, which the follower passes straight) takes the nearest segment at
  // least that long: a start there faces along the hallway, not across it.
  const auto long_enough = [&](int k) {
    return (axis_[k].b_in - axis_[k].a_in).norm() >= hallway_width_in_;
  };
  int j = axis_of_edge_[e];
  if (j < 0 || !long_enough(j)) {
    // The nearest long segment; with none, the nearest of any.
    double nearest_long = std::numeric_limits<double>::infinity();
    double nearest_any = nearest_long;
    int long_j = -1, any_j = 0;
    for (int k = 0; k < static_cast<int>(axis_.size()); ++k) {
      const double d = SegmentDistance(on_wall, axis_[k].a_in, axis_[k].b_in);
      if (d < nearest_any) nearest_any = d, any_j = k;
      if (d < nearest_long && long_enough(k)) nearest_long = d, long_j = k;
    }
    j = long_j >= 0 ? long_j : (j >= 0 ? j : any_j);
  }
  const Eigen::Vector2d a = axis_[j].a_in, b = axis_[j].b_in;
  double t = 0.0;
  SegmentDistance(on_wall, a, b, &t);
  const Eigen::Vector2d p = a + t * (b - a);
  const Eigen::Vector2d u = Unit(a, b);
  // Facing against ring order puts the wall on the base's left, where the camera looks.
  return world::Pose2d{p.x(), p.y(), std::atan2(-u.y(), -u.x())};
}

WorldSim::WallSeen WorldSim::Look(const Eigen::Vector2d& p, const Eigen::Vector2d& ray,
                                  int only) const {
  WallSeen seen;
  double best_t = 2.0 * hallway_width_in_;
  const int first = only < 0 ? 0 : only;
  const int last = only < 0 ? static_cast<int>(walls_.size()) - 1 : only;
  // The start ring first: where two rings share a line (a corridor's mouth), it is its.
  for (int r = first; r <= last; ++r) {
    const std::vector<Eigen::Vector2d>& n = walls_[r].node_in;
    for (int e = 0; e + 1 < static_cast<int>(n.size()); ++e) {
      const double hit = RaySegment(p, ray, n[e], n[e + 1]);
      if (hit > 0.0 && hit < best_t) {
        best_t = hit;
        seen = {r, e, p + ray * hit, true};
      }
    }
  }
  if (seen.edge >= 0) return seen;
  double nearest = std::numeric_limits<double>::infinity();
  for (int r = first; r <= last; ++r) {
    const std::vector<Eigen::Vector2d>& n = walls_[r].node_in;
    for (int e = 0; e + 1 < static_cast<int>(n.size()); ++e) {
      double f = 0.0;
      const double d = SegmentDistance(p, n[e], n[e + 1], &f);
      if (d < nearest) {
        nearest = d;
        seen = {r, e, n[e] + f * (n[e + 1] - n[e]), false};
      }
    }
  }
  return seen;
}

double WorldSim::OffsetAlong(const WallSeen& seen) const {
  const RingWalls& w = walls_[seen.ring];
  const Eigen::Vector2d a = w.node_in[seen.edge], b = w.node_in[seen.edge + 1];
  const double metric = w.metric_in[seen.edge], length = (b - a).norm();
  return length > 0.0 ? std::clamp((seen.foot - a).norm() / length * metric, 0.0, metric) : 0.0;
}

double WorldSim::Clearance(const Eigen::Vector2d& p) const {
  double best = std::numeric_limits<double>::infinity();
  for (int i : obstacle_panels_) {
    const world::Panel& panel = scene_->panels()[i];
    best = std::min(best, SegmentDistance(p, panel.p0_in, panel.p1_in));
  }
  return best;
}

void WorldSim::Step(double dt_s, double left_ftps, double right_ftps) {
  if (!(dt_s > 0.0) || !std::isfinite(left_ftps) || !std::isfinite(right_ftps)) return;
  const double vmax = models_.base.max_speed_ftps;
  const double dl = FeetToInches(std::clamp(left_ftps, -vmax, vmax)) * dt_s;
  const double dr = FeetToInches(std::clamp(right_ftps, -vmax, vmax)) * dt_s;
  double slip_l = 0.0, slip_r = 0.0;
  if (models_.base.slip_stddev > 0.0) {
    std::normal_distribution<double> slip(0.0, models_.base.slip_stddev);
    slip_l = slip(rng_);
    slip_r = slip(rng_);
  }
  const world::Pose2d next = world::IntegrateWheels(X_WR_, dl * (1.0 + slip_l),
                                                    dr * (1.0 + slip_r),
                                                    models_.base.wheel_base_in);
  const double clear_before = Clearance(X_WR_.position());
  const double clear_after = Clearance(next.position());
  if (clear_after < footprint_radius_in_ && clear_after < clear_before - 1e-9) {
    // Against a wall: the base stalls, the wheels do not turn.
    if (!in_contact_) ++collisions_;
    in_contact_ = true;
    return;
  }
  const Eigen::Vector2d moved = next.position() - X_WR_.position();
  // The travel direction: the way the base's forward axis points, or the opposite way when
  // it drives backward. Turning in place (the wheels' travel cancels) leaves it as it was.
  const double ds = 0.5 * (dl + dr);
  if (std::abs(ds) > 1e-3 * std::max(std::abs(dl), std::abs(dr))) {
    last_motion_ = Eigen::Vector2d(std::cos(X_WR_.theta_rad), std::sin(X_WR_.theta_rad)) *
                   (ds > 0.0 ? 1.0 : -1.0);
  }
  distance_in_ += moved.norm();
  left_travel_in_ += dl;
  right_travel_in_ += dr;
  X_WR_ = next;
  in_contact_ = clear_after < footprint_radius_in_;
}

void WorldSim::Teleport(double ring_position_in) {
  X_WR_ = AxisPoseAbreast(ring_position_in);
  in_contact_ = false;
}

double WorldSim::RingPosition() const {
  const SimTruth t = Truth();
  return edge_start_in_[t.edge_index] + t.offset_in;
}

std::array<float, 24> WorldSim::Sonar() {
  std::array<float, 24> out{};
  const std::vector<world::SonarReading> readings =
      config_.sonar_surface_errors ? sonar_.Sense(*scene_, X_WR_, sonar_errors_, rng_)
                                   : sonar_.SenseExact(*scene_, X_WR_);
  for (size_t k = 0; k < readings.size() && k < out.size(); ++k) {
    out[k] = readings[k].valid ? static_cast<float>(readings[k].range_in) : 0.0f;
  }
  return out;
}

std::vector<std::uint8_t> WorldSim::RenderFrame() {
  world::Illumination base;
  base.noise_stddev = config_.image_noise_sigma;
  const world::Illumination light = world::DrawIllumination(config_.realism, base, light_rng_);
  const world::RenderedFrame frame = camera_->Render(*scene_, X_WR_, light, rng_);
  const cv::Mat img = frame.image.isContinuous() ? frame.image : frame.image.clone();
  return std::vector<std::uint8_t>(img.data, img.data + img.total());
}

SimTruth WorldSim::Truth() const {
  SimTruth t;
  t.X_WR = X_WR_;
  t.ring = ring_;
  t.distance_in = distance_in_;
  t.collisions = collisions_;
  t.in_contact = in_contact_;
  const Eigen::Vector2d p = X_WR_.position();

  // The edge the camera looks at: the first crossing of the optical axis with the mapped
  // wall polyline, within twice the hallway's width (see SimTruth::edge_index).
  const double yaw = X_WR_.theta_rad + DegToRad(models_.camera.mount_yaw_deg);
  const Eigen::Vector2d ray{std::cos(yaw), std::sin(yaw)};
  const WallSeen own = Look(p, ray, 0);
  t.optical_axis_on_wall = own.on_axis;
  t.edge_index = own.edge;
  t.offset_in = OffsetAlong(own);

  // The nearest stretch of the hallway axis. The travel direction is judged on it (at a
  // corner, where two stretches are equally near, on the one the base travelled along).
  const int segments = static_cast<int>(axis_.size());
  std::vector<double> distance(segments), along_axis(segments);
  int nearest = 0;
  for (int j = 0; j < segments; ++j) {
    distance[j] = SegmentDistance(p, axis_[j].a_in, axis_[j].b_in, &along_axis[j]);
    if (distance[j] < distance[nearest]) nearest = j;
  }
  // The axis of a corridor outline runs down the corridor and back, one stretch per side:
  // of stretches about as near, the one whose wall the base keeps on its left.
  const Eigen::Vector2d facing{std::cos(X_WR_.theta_rad), std::sin(X_WR_.theta_rad)};
  const auto facing_along = [&](int j) { return -facing.dot(Unit(axis_[j].a_in, axis_[j].b_in)); };
  for (int j = 0; j < segments; ++j) {
    if (distance[j] < distance[nearest] + 1.0 && facing_along(j) > facing_along(nearest) + 0.5) {
      nearest = j;
    }
  }
  // The travel direction is judged on a stretch of the side the camera watches: a corridor
  // outline's other side runs along the same line the other way round, and judged on it
  // the direction would come out reversed.
  double best_alignment = -1.0;
  for (int j = 0; j < segments; ++j) {
    const double along = last_motion_.dot(Unit(axis_[j].a_in, axis_[j].b_in));
    if (distance[j] < distance[nearest] + 1.0 && facing_along(j) > -0.5 &&
        std::abs(along) > best_alignment) {
      best_alignment = std::abs(along);
      t.forward_in_ring = along > 0.0;
    }
  }
  // The floor-wide look the pose is judged on. On another corridor's wall the direction is
  // that wall's ring order against the last translation.
  const WallSeen seen = walls_.size() > 1 ? Look(p, ray, -1) : own;
  const RingWalls& seen_walls = walls_[seen.ring];
  t.seen_ring_id = seen_walls.id;
  t.seen_edge_index = seen.edge;
  t.seen_offset_in = OffsetAlong(seen);
  t.seen_ring_edge_count = static_cast<int>(seen_walls.node_in.size()) - 1;
  t.seen_forward_in_ring =
      seen.ring == 0 ? t.forward_in_ring
                     : last_motion_.dot(Unit(seen_walls.node_in[seen.edge],
                                             seen_walls.node_in[seen.edge + 1])) > 0.0;
  const Eigen::Vector2d a = axis_[nearest].a_in, b = axis_[nearest].b_in;
  const Eigen::Vector2d u = Unit(a, b);
  t.lateral_offset_in = (p - a).dot(-Left(u));
  t.heading_error_rad = WrapPi(X_WR_.theta_rad - std::atan2(-u.y(), -u.x()));
  if (corridor_outline_ && std::abs(t.heading_error_rad) > kPi / 2.0) {
    t.heading_error_rad = WrapPi(t.heading_error_rad + kPi);
  }
  t.axis_position_in = axis_start_in_[nearest] + along_axis[nearest] * (b - a).norm();
  t.in_ring_hallway = distance[nearest] <= 0.5 * hallway_width_in_;
  // Corners are where the axis bends (an open ring's ends are not).
  t.corner_distance_in = std::numeric_limits<double>::infinity();
  for (int j = closed_ ? 0 : 1; j < static_cast<int>(axis_.size()); ++j) {
    t.corner_distance_in = std::min(t.corner_distance_in, (p - axis_[j].a_in).norm());
  }
  return t;
}

}  // namespace stickrep::virtual_robot
