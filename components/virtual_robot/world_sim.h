#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "sensing/robot_config.h"
#include "stickrep/map.h"
#include "world/camera_renderer.h"
#include "world/map_world.h"
#include "world/realism.h"
#include "world/robot_models.h"
#include "world/scene.h"
#include "world/sonar_error_adapter.h"
#include "world/sonar_ring.h"

namespace stickrep::virtual_robot {

// How the simulated hallway and its robot are set up.
struct WorldSimConfig {
  std::string ring_id;               // empty: the map's first ring
  double hallway_width_in = 120.0;   // the opposite wall stands this far from the mapped one
  double open_door_fraction = 0.0;   // share of doors drawn open (§4.1.2)
  double image_noise_sigma = 2.0;    // grey levels
  bool sonar_surface_errors = true;  // Tables 4.2/4.3 error model, else exact ranges
  double wheel_slip_stddev = 0.01;   // per-step wheel slip (odometry error)
  // Where the robot starts relative to the hallway axis abreast of the start position:
  // off the axis toward the mapped wall (negative: toward the opposite wall) and turned
  // counter-clockwise from the axis direction. 0, 0: on the axis, aligned (A3, A4 of §6.3).
  double start_lateral_offset_in = 0.0;
  double start_heading_error_deg = 0.0;
  // The clutter of real hallways (world::RealismOptions): each feature a switch, drawn from
  // the seed. The default is the clean hallway.
  world::RealismOptions realism;
};

// Where the robot really is, in map terms.
struct SimTruth {
  world::Pose2d X_WR;        // building frame
  int ring = 0;
  // The edge the camera's optical axis meets first on the ring's mapped wall polyline and
  // how far along it (ring order, scaled to the edge's metric). When the axis meets no
  // mapped wall (looking into a crossing), or meets one only across an open hall (farther
  // than twice the hallway's width: the base has turned at the hall's corner and the wall
  // it follows next begins ahead), the edge nearest the robot instead.
  int edge_index = 0;
  double offset_in = 0.0;
  bool optical_axis_on_wall = false;
  // The same look taken over every corridor of the floor (a corridor outline's world is
  // the whole building, and the base may go on from its ring into another corridor): the
  // ring, edge and travel direction a localized pose is judged against. They are the start
  // ring's edge_index and forward_in_ring while the camera looks at the start ring.
  std::string seen_ring_id;
  int seen_edge_index = 0;
  double seen_offset_in = 0.0;  // along that edge, ring order, scaled to its metric
  int seen_ring_edge_count = 0;
  bool seen_forward_in_ring = false;
  double distance_in = 0.0;       // true path length travelled (both directions count)
  // The base last travelled in ring order (judged on the edge above; turning in place
  // keeps the direction the base travelled before the turn).
  bool forward_in_ring = false;
  // Relative to the nearest segment of the hallway axis (the mapped wall, its steps under
  // 3 ft passed straight, offset by half the hallway, mitred at corners): the signed offset of the
  // base centre, positive toward the mapped wall, and the heading error of the base's forward axis
  // from the axis direction that keeps the mapped wall on the left (against ring order), CCW
  // positive. On a corridor outline, whose camera may watch either wall, the heading error is taken
  // from the nearer of the corridor's two directions (within ±90°): where one side lies open (a
  // lobby's mouth) the nearest stretch is the other side's, and a base travelling along the
  // corridor is on its axis either way.
  double lateral_offset_in = 0.0;
  double heading_error_rad = 0.0;
  // Path length along the axis of the base's foot on it (ring order, from the start of the
  // axis), and the distance from the base centre to the nearest bend of the axis (a corner
  // the robot turns at; steps passed straight are not corners).
  double axis_position_in = 0.0;
  double corner_distance_in = 0.0;
  // The base centre lies within half the hallway's width of the nearest axis segment (the
  // segment, not its line): it has not left the ring's hallway for another corridor, a hall
  // or through an open end, where the offset and heading above say nothing of how well it
  // keeps to a hallway.
  bool in_ring_hallway = true;
  // Contacts of the base's footprint with the scene's walls so far, and whether it touches
  // one now.
  int collisions = 0;
  bool in_contact = false;
};

// The simulated robot in a hallway built from one ring of the map (world::BuildRingWorld):
// walls, doors and their frames as planes, the sonar ring cast against them with the
// surface/incidence errors of §4.3, and the camera rendered with the configured lens, noise
// and distortion. The base moves freely in the plane: its pose (x, y, θ) is integrated from
// the two wheel speeds (each clamped to the top speed) with seeded per-wheel slip, so the
// encoders report the commanded travel and the robot moves the slipped one. Nothing holds
// it in the hallway: staying on the axis and turning at corners is the locomotion
// process's job. The camera looks left of the base's heading (configs/robot.yaml), and the
// hallway lies on the left of ring order, so the base must face against ring order to see
// the ring's wall.
//
// The footprint is a disc of the sonar head's radius (configs/robot.yaml gives no other
// outline of the base). A step that would bring it into a wall, door leaf or frame of the
// scene (or deeper into one) is not taken: the base stalls there, its wheels do not turn,
// and the contact is counted. Steps that leave the wall are taken.
// A start pose that puts the base against a wall: the start can be drawn again.
class ImpossibleStart : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

class WorldSim {
 public:
  // Throws ImpossibleStart for a start pose that touches a wall, std::invalid_argument for an
  // unknown ring; InputError comes from the configs.
  WorldSim(const map::Map& map, const sensing::RobotConfig& robot, const WorldSimConfig& config,
           double start_offset_in, std::uint64_t seed);

  // Advances by dt_s with the given wheel speeds (each clamped to the base's top speed).
  void Step(double dt_s, double left_ftps, double right_ftps);
  // Puts the robot on the hallway axis abreast of a place along the ring (a kidnapping),
  // aligned with the axis and facing against ring order; encoders keep counting.
  void Teleport(double ring_position_in);
  // Arc length along the ring (ring order) of the optical axis's foot (Truth()).
  double RingPosition() const;
  std::array<float, 24> Sonar();
  // A mono8 frame, row-major, width x height, no padding.
  std::vector<std::uint8_t> RenderFrame();
  double left_travel_in() const { return left_travel_in_; }
  double right_travel_in() const { return right_travel_in_; }
  SimTruth Truth() const;
  const world::Pose2d& pose() const { return X_WR_; }
  double ring_length_in() const { return length_in_; }
  double axis_length_in() const { return axis_start_in_.back(); }
  const std::string& ring_id() const { return ring_id_; }
  int edge_count() const { return static_cast<int>(edge_start_in_.size()) - 1; }
  int image_width_px() const { return models_.camera.width_px; }
  int image_height_px() const { return models_.camera.height_px; }
  double footprint_radius_in() const { return footprint_radius_in_; }
  double max_speed_ftps() const { return models_.base.max_speed_ftps; }

 private:
  world::Pose2d AxisPoseAbreast(double ring_position_in) const;
  // The mapped walls of one ring, as the truth looks at them.
  struct RingWalls {
    std::string id;
    std::vector<Eigen::Vector2d> node_in;  // node i starts edge i; the last closes the ring
    std::vector<double> metric_in;         // edge i's
  };
  struct WallSeen {
    int ring = -1;  // index into walls_
    int edge = -1;
    Eigen::Vector2d foot{0.0, 0.0};
    bool on_axis = false;  // met by the optical axis (else the nearest wall)
  };
  // The first wall of `walls_[only]` (or of every ring when only < 0) the ray from p meets
  // within twice the hallway's width; else the nearest.
  WallSeen Look(const Eigen::Vector2d& p, const Eigen::Vector2d& ray, int only) const;
  // How far along its edge (ring order, scaled to the edge's metric) the wall was met.
  double OffsetAlong(const WallSeen& seen) const;
  void BuildAxis(const map::Ring& ring);
  // Distance from p to the nearest wall, frame or leaf of the scene at the base's height.
  double Clearance(const Eigen::Vector2d& p) const;

  WorldSimConfig config_;
  world::RobotModels models_;
  std::unique_ptr<world::Scene> scene_;
  std::unique_ptr<world::CameraRenderer> camera_;
  world::SonarRingSimulator sonar_;
  world::SurfaceTableSonarErrorModel sonar_errors_;
  std::string ring_id_;
  int ring_ = 0;
  bool closed_ = true;
  bool corridor_outline_ = false;  // the ring outlines a corridor (both walls, map format 2)
  double hallway_width_in_ = 0.0;  // the ring's, or the settings' when it gives none
  // walls_[0] is the start ring; with a corridor outline the floor's other rings follow.
  std::vector<RingWalls> walls_;
  std::vector<Eigen::Vector2d> node_in_;   // node i starts edge i
  // The hallway axis: midway between the mapped wall (shallow steps passed straight) and
  // the opposite wall, in ring order; the axis segment of each edge (-1: its run collapsed);
  // path length along the axis to the start of each segment (back(): the whole axis).
  std::vector<world::OffsetSegment> axis_;
  std::vector<int> axis_of_edge_;
  std::vector<double> axis_start_in_;
  std::vector<double> edge_start_in_;      // arc length along the ring; back() == length
  std::vector<int> obstacle_panels_;       // scene panels the footprint can touch
  double length_in_ = 0.0;
  double footprint_radius_in_ = 7.5;
  world::Pose2d X_WR_;
  double left_travel_in_ = 0.0, right_travel_in_ = 0.0, distance_in_ = 0.0;
  Eigen::Vector2d last_motion_{0.0, 0.0};  // travel direction of the last translation
  int collisions_ = 0;
  bool in_contact_ = false;
  std::mt19937_64 rng_;
  std::mt19937_64 light_rng_;  // each frame's light (realism.illumination)
};

}  // namespace stickrep::virtual_robot
