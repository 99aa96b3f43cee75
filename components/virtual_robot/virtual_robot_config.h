#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/strict_yaml.h"
#include "stickrep/map.h"
#include "virtual_robot/world_sim.h"

namespace stickrep::virtual_robot {

// The recording a replaying virtual robot plays (the `replay` section).
struct ReplaySourceConfig {
  std::string file;        // a stickrep-record recording
  double rate = 1.0;       // recorded seconds per wall second
  double start_s = 0.0;    // skipped at the start of the recording
  double duration_s = 0.0; // 0: to the end
  bool loop = false;
};

// The virtual robot's settings (configs/virtual_robot.yaml).
struct VirtualRobotConfig {
  bool replay = false;            // source: replay (else simulated)
  ReplaySourceConfig recording;   // read when replay
  std::uint64_t seed = 1;
  double start_offset_in = -1.0;  // along the ring; -1: drawn from the seed
  WorldSimConfig world;           // start_lateral_offset_in/heading filled by DrawStart
  double start_lateral_offset_max_in = 0.0;
  double start_heading_error_max_deg = 0.0;
  double real_time_factor = 1.0;
  double sim_rate_hz = 50.0;
  double encoder_rate_hz = 20.0;
  double sonar_rate_hz = 10.0;
  double camera_rate_hz = 5.0;
  double wheel_command_timeout_s = 0.5;
  double kidnap_after_localized_s = -1.0;  // -1: never
  double kidnap_jump_in = 0.0;
  std::string summary_png;
};

// Reads the `virtual_robot` section; every key required, unknown keys rejected (InputError
// with file, line and key). With `source: replay` the `replay` section names the recording.
VirtualRobotConfig LoadVirtualRobotConfig(const StrictYaml& section);

// Where a run starts: along the ring (drawn uniformly over its length when the config's
// start_offset_in is -1) and off the axis and turned (drawn within the config's bounds),
// all from the seed. The virtual robot process and the closed-loop run draw alike.
struct StartPlacement {
  double ring_position_in = 0.0;
  double lateral_offset_in = 0.0;
  double heading_error_deg = 0.0;
};
// `attempt` 0 is the seed's own draw; a start found impossible is drawn again with the next
// attempt (PlaceRobot).
StartPlacement DrawStart(const VirtualRobotConfig& config, const map::Ring& ring,
                         int attempt = 0);

// The simulated world with the robot at a drawn start. A start that puts the base against a
// wall is drawn again (up to kMaxStartDraws times, each refusal kept in `redraws`); after
// that the last ImpossibleStart is thrown.
struct PlacedRobot {
  std::unique_ptr<WorldSim> sim;
  StartPlacement start;
  std::vector<std::string> redraws;
};
inline constexpr int kMaxStartDraws = 20;
PlacedRobot PlaceRobot(const map::Map& map, const sensing::RobotConfig& robot,
                       const VirtualRobotConfig& config, int ring);

// Whether a localized pose (ring id, edge, travel direction) names where the robot truly
// is: the same ring and direction as where the camera looks over the whole floor
// (SimTruth::seen_ring_id), and that edge or a neighbour (the pose may be published while
// a node is crossed).
bool PoseMatchesTruth(const std::string& ring_id, int edge, bool forward, const SimTruth& truth);
// The same against a truth given as its ring, edge and direction (a recorded GroundTruth).
bool PoseMatchesTruth(const std::string& ring_id, int edge, bool forward,
                      const std::string& truth_ring_id, int truth_edge, bool truth_forward,
                      int ring_edge_count);

}  // namespace stickrep::virtual_robot
