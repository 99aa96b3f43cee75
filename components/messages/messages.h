#pragma once

// The samples StickRep's components exchange, one C++ type per IDL type a component reads or
// writes (idl/*.idl has the field-by-field meaning). A component sees only these; the DDS
// adapters convert them to and from the IDL types at the boundary (convert/), and the
// in-process executor hands them from one component to the next unchanged.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sensing/door_classifier.h"
#include "stickrep/map.h"
#include "sonar/sonar_gate.h"

namespace stickrep::message {

// The header of every sample: when it describes (simulated time on the virtual robot) and
// the writer's sequence number (set by the transport).
struct Header {
  int64_t stamp_ns = 0;
  uint32_t sequence = 0;
};

// --- sensors (sensors.idl) ---

struct SonarEcho {
  Header header;
  std::array<float, sonar::kRingSize> range_in{};  // <= 0: no echo
};

struct SonarScan {
  Header header;
  std::array<float, sonar::kRingSize> range_in{};
  std::array<sonar::ReadingState, sonar::kRingSize> state{};
  int valid_count = 0;
};

struct Image {
  Header header;
  uint32_t width_px = 0;
  uint32_t height_px = 0;
  std::string encoding;
  uint32_t step_bytes = 0;
  std::vector<std::uint8_t> data;
};

// --- base (base.idl) ---

struct WheelCommand {
  Header header;
  double left_speed_ftps = 0.0;
  double right_speed_ftps = 0.0;
};

struct EncoderReading {
  Header header;
  double left_travel_in = 0.0;
  double right_travel_in = 0.0;
};

enum class MotionMode : std::uint8_t { kStop, kVelocity, kFollowHallway };

struct MotionCommand {
  Header header;
  MotionMode mode = MotionMode::kStop;
  double linear_speed_ftps = 0.0;
  double angular_rate_radps = 0.0;
};

enum class LocomotionState : std::uint8_t {
  kStopped, kVelocity, kNoScan, kFollowing, kStopping, kTurning, kObstacle
};

struct MotionState {
  Header header;
  MotionMode mode = MotionMode::kStop;
  LocomotionState state = LocomotionState::kStopped;
  int travel_sign = 1;
  bool offset_valid = false;
  double lateral_offset_in = 0.0;
  bool heading_valid = false;
  double heading_error_deg = 0.0;
  bool in_envelope = false;
  double commanded_speed_ftps = 0.0;
  double linear_speed_ftps = 0.0;
  double angular_rate_radps = 0.0;
  std::string message;
};

struct Odometry {
  Header header;
  double x_in = 0.0, y_in = 0.0, heading_rad = 0.0;  // odometry frame
  double distance_in = 0.0;
  double linear_speed_ftps = 0.0;
  double angular_rate_radps = 0.0;
};

// --- perception (perception.idl) ---

struct LandmarkObservation {
  Header header;
  sensing::DoorClass door_class = sensing::DoorClass::k30;
  double width_in = 0.0;
  double confidence = 0.0;
  double left_jamb_px = 0.0, right_jamb_px = 0.0;
  double range_in = 0.0;
  double center_offset_in = 0.0;
  double look_angle_rad = 0.0;
  bool in_envelope = false;
  double odometry_distance_in = 0.0;
  int64_t image_stamp_ns = 0;
  map::DoorMark mark = map::DoorMark::kUnknown;  // the leaf's mark (Table 6.8)
};

// --- localization (localization.idl) ---

enum class LocalizationStatus : std::uint8_t { kRecovering, kLocalized, kLost };

struct PoseHypothesis {
  std::string ring_id;
  int edge_index = 0;
  bool forward = true;
  double offset_in = 0.0;
  double x_in = 0.0, y_in = 0.0, heading_rad = 0.0;  // building frame
  double probability = 0.0;
};

// localization/pose: the status and the best place.
struct LocalizationPose {
  Header header;
  LocalizationStatus status = LocalizationStatus::kRecovering;
  int candidate_count = 0;
  PoseHypothesis best;  // meaningful when there is a candidate
  double confidence = 0.0;
  int edges_sensed = 0;
  std::string message;
};

// localization/hypotheses: the top candidates, best first.
struct PoseHypotheses {
  Header header;
  std::vector<PoseHypothesis> hypotheses;
};

// --- mission (mission.idl) ---

struct MissionGoal {
  Header header;
  std::string goal_id;
  std::string target;
};

enum class MissionState : std::uint8_t {
  kWaitingForComponents, kAligning, kRecoveringPose, kLocalized, kExecutingGoal, kGoalReached,
  kStoppedFault, kLinkLost
};

struct MissionStatus {
  Header header;
  MissionState state = MissionState::kWaitingForComponents;
  std::string goal_id;
  std::string message;
};

struct MissionGoalResult {
  Header header;
  std::string goal_id;
  std::string target;
  bool accepted = false;
  std::string reason;
};

// --- system (system.idl) ---

enum class ComponentState : std::uint8_t { kUnconfigured, kInactive, kActive, kFinalized };

struct ComponentStatus {
  Header header;
  std::string component_name;
  ComponentState state = ComponentState::kUnconfigured;
  uint64_t samples_in = 0, samples_out = 0, samples_dropped = 0;
  std::string message;
  std::string host;
};

// sim/ground_truth: where the virtual robot really is (building frame; the place a pose is
// judged on).
struct GroundTruth {
  Header header;
  double x_in = 0.0, y_in = 0.0, heading_rad = 0.0;
  std::string ring_id;
  int edge_index = 0;
  double offset_in = 0.0;
  double distance_in = 0.0;
  double lateral_offset_in = 0.0;
  double heading_error_deg = 0.0;
  int collisions = 0;
  bool forward_in_ring = false;
};

}  // namespace stickrep::message
