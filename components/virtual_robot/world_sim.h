#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "sensing/robot_config.h"
#include "stickrep/map.h"
#include "world/camera_renderer.h"
#include "world/map_world.h"
#include "world/robot_models.h"
#include "world/scene.h"
#include "world/sonar_error_adapter.h"
#include "world/sonar_ring.h"

namespace stickrep::virtual_robot {

// How the simulated hallway and its robot are set up.
struct WorldSimConfig {
  std::string ring_id;               // empty: the map's first ring
  double hallway_width_in = 120.0;   // the robot runs on its axis (A4 of §6.3)
  double open_door_fraction = 0.0;   // share of doors drawn open (§4.1.2)
  double image_noise_sigma = 2.0;    // grey levels
  bool sonar_surface_errors = true;  // Tables 4.2/4.3 error model, else exact ranges
  double wheel_slip_stddev = 0.01;   // per-step wheel slip (odometry error)
};

// Where the robot really is, in map terms.
struct SimTruth {
  world::Pose2d X_WR;        // building frame
  int ring = 0;
  int edge_index = 0;        // the edge the optical axis looks at
  double offset_in = 0.0;    // along that edge, in ring order
  double distance_in = 0.0;  // path length travelled
  bool forward_in_ring = false;  // travelling in ring order
};

// The simulated robot in a hallway built from one ring of the map (world::BuildRingWorld):
// walls, doors and their frames as planes, the sonar ring cast against them with the
// surface/incidence errors of §4.3, and the camera rendered with the configured lens, noise
// and distortion. The base is held on the hallway axis and aligned with it — assumptions A3
// and A4 of §6.3 — and moves along the axis by the distance its wheels travel, with seeded
// wheel slip: the encoders report the commanded travel, the robot moves the slipped one.
// The camera looks left of the base's heading (configs/robot.yaml), and the hallway lies on
// the left of ring order, so the base faces against ring order to see the ring's wall.
// The axis is the wall offset by half the hallway, mitred at corners: at a concave corner
// the robot turns before reaching the wall ahead instead of running into it.
class WorldSim {
 public:
  // Throws std::invalid_argument for an unknown ring; InputError comes from the configs.
  WorldSim(const map::Map& map, const sensing::RobotConfig& robot, const WorldSimConfig& config,
           double start_offset_in, std::uint64_t seed);

  // Advances by dt_s with the given wheel speeds (clamped to the base's top speed).
  void Step(double dt_s, double left_ftps, double right_ftps);
  // Puts the robot at another place along the ring (a kidnapping); encoders keep counting.
  void Teleport(double ring_position_in);
  // Arc length along the ring (ring order) of the optical axis's foot.
  double RingPosition() const;
  std::array<float, 24> Sonar();
  // A mono8 frame, row-major, width x height, no padding.
  std::vector<std::uint8_t> RenderFrame();
  double left_travel_in() const { return left_travel_in_; }
  double right_travel_in() const { return right_travel_in_; }
  SimTruth Truth() const;
  double ring_length_in() const { return length_in_; }
  const std::string& ring_id() const { return ring_id_; }
  int edge_count() const { return static_cast<int>(edge_start_in_.size()) - 1; }
  int image_width_px() const { return models_.camera.width_px; }
  int image_height_px() const { return models_.camera.height_px; }

 private:
  world::Pose2d PoseAt(double ring_position_in) const;
  void BuildAxis();
  int SegmentAt(double path_in) const;
  double Wrap(double path_in) const;
  double PathFromRing(double ring_position_in) const;

  WorldSimConfig config_;
  world::RobotModels models_;
  std::unique_ptr<world::Scene> scene_;
  std::unique_ptr<world::CameraRenderer> camera_;
  world::SonarRingSimulator sonar_;
  world::SurfaceTableSonarErrorModel sonar_errors_;
  std::string ring_id_;
  int ring_ = 0;
  bool closed_ = true;
  std::vector<Eigen::Vector2d> node_in_;   // node i starts edge i
  std::vector<Eigen::Vector2d> axis_in_;   // the hallway axis point abreast of node i
  std::vector<double> axis_start_in_;      // path length along the axis to axis_in_[i]
  std::vector<double> edge_start_in_;      // arc length along the ring; back() == length
  double length_in_ = 0.0;
  double position_in_ = 0.0;               // path length along the hallway axis
  double left_travel_in_ = 0.0, right_travel_in_ = 0.0, distance_in_ = 0.0;
  int travel_sign_ = 0;
  std::mt19937_64 rng_;
};

}  // namespace stickrep::virtual_robot
