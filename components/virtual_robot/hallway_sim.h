#pragma once

#include <array>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "stickrep/map.h"

namespace stickrep::virtual_robot {

// What the simulated robot carries (from configs/robot.yaml).
struct SimRobotConfig {
  double wheel_base_in = 14.0;
  double max_speed_ftps = 2.6;
  int sonar_count = 24;
  double sonar_spacing_deg = 15.0;
  double head_radius_in = 7.5;
  double sonar_max_range_in = 420.0;
  int coaxial_sensor = 0;
  int image_width_px = 512;
  int image_height_px = 480;
  double fov_deg = 55.817;
  double camera_height_in = 40.0;
};

// The simulated hallway: one ring of the map laid out straight ("cutting and stretching out
// a hallway into a line", §3.3), its edges on the wall the camera faces, a plain wall
// opposite, and the robot on the hallway axis. Doors are closed and drawn as a darker face
// between two dark jambs.
struct SimWorldConfig {
  std::string ring_id;              // empty: the map's first ring
  double hallway_width_in = 96.0;
  double door_height_in = 84.0;
  double ceiling_height_in = 108.0;
  double jamb_width_in = 2.0;       // door frame, outside the opening
  double image_noise_sigma = 2.0;   // grey levels
};

// One sonar ring reading: range per transducer, 0 for no echo.
using SonarRanges = std::array<float, 24>;

// Where the robot really is, in map terms.
struct SimTruth {
  double x_in = 0.0;                // along the straightened ring, from the start of edge 0
  double y_in = 0.0;                // off the hallway axis, positive toward the mapped wall
  double heading_rad = 0.0;         // 0: facing the ring's edge order
  int edge_index = 0;               // the edge on the optical axis
  double offset_in = 0.0;           // how far along that edge
  double distance_in = 0.0;         // path length travelled
};

// A minimal simulated robot in a straightened hallway: differential-drive kinematics, a
// sonar ring ray-cast against the two hallway walls, and a pinhole camera facing the mapped
// wall. The body keeps facing along the hallway with the camera toward the wall; the robot
// travels forward or backward along it (§6.3: "either left to right or right to left
// relative to the orientation of the camera").
class HallwaySim {
 public:
  // Throws std::invalid_argument if the ring is unknown, open rings are fine.
  HallwaySim(const map::Map& map, const SimWorldConfig& world, const SimRobotConfig& robot,
             double start_x_in, uint64_t seed);

  // Advances the base by dt_s with the given wheel speeds (clamped to the top speed).
  void Step(double dt_s, double left_ftps, double right_ftps);
  SonarRanges Sonar() const;
  // A mono8 frame, row-major, width x height.
  std::vector<uint8_t> RenderFrame();
  double left_travel_in() const { return left_travel_in_; }
  double right_travel_in() const { return right_travel_in_; }
  SimTruth Truth() const;
  double ring_length_in() const { return length_in_; }
  const std::string& ring_id() const { return ring_id_; }
  int edge_count() const { return static_cast<int>(is_door_.size()); }

 private:
  double WrapX(double x) const;
  double RayRange(double bearing_rad) const;

  SimWorldConfig world_;
  SimRobotConfig robot_;
  std::string ring_id_;
  bool closed_ = true;
  std::vector<double> edge_start_in_;  // x where each edge starts; back() == length
  std::vector<bool> is_door_;
  std::vector<bool> is_double_;       // double doors show a meeting stile between leaves
  double length_in_ = 0.0;
  double x_in_ = 0.0, y_in_ = 0.0, heading_rad_ = 0.0;
  double left_travel_in_ = 0.0, right_travel_in_ = 0.0, distance_in_ = 0.0;
  std::mt19937_64 rng_;
};

}  // namespace stickrep::virtual_robot
