#include "console/message_json.h"

#include <cstdint>

namespace stickrep::console {

using nlohmann::json;

namespace {

json Header(const msgs::SampleHeader& h) {
  return {{"stamp_ns", h.stamp_ns()}, {"sequence_number", h.sequence_number()}};
}

json Pose(const msgs::Pose2D& p) {
  return {{"x_in", p.x_in()}, {"y_in", p.y_in()}, {"heading_rad", p.heading_rad()}};
}

json Hypothesis(const msgs::PoseHypothesis& h) {
  return {{"ring_id", h.ring_id()},     {"edge_index", h.edge_index()},
          {"forward", h.forward()},     {"offset_in", h.offset_in()},
          {"pose", Pose(h.pose())},     {"probability", h.probability()}};
}

}  // namespace

const char* Name(msgs::DoorClass c) {
  switch (c) {
    case msgs::DOOR_REJECTED: return "DOOR_REJECTED";
    case msgs::DOOR_30: return "DOOR_30";
    case msgs::DOOR_32: return "DOOR_32";
    case msgs::DOOR_36: return "DOOR_36";
    case msgs::DOOR_40: return "DOOR_40";
    case msgs::DOOR_30_30: return "DOOR_30_30";
    case msgs::DOOR_36_36: return "DOOR_36_36";
  }
  return "?";
}
const char* Name(msgs::LocalizationStatus s) {
  switch (s) {
    case msgs::LOCALIZATION_RECOVERING: return "RECOVERING";
    case msgs::LOCALIZATION_LOCALIZED: return "LOCALIZED";
    case msgs::LOCALIZATION_LOST: return "LOST";
  }
  return "?";
}
const char* Name(msgs::MissionState s) {
  switch (s) {
    case msgs::MISSION_WAITING_FOR_COMPONENTS: return "WAITING_FOR_COMPONENTS";
    case msgs::MISSION_ALIGNING: return "ALIGNING";
    case msgs::MISSION_RECOVERING_POSE: return "RECOVERING_POSE";
    case msgs::MISSION_LOCALIZED: return "LOCALIZED";
    case msgs::MISSION_EXECUTING_GOAL: return "EXECUTING_GOAL";
    case msgs::MISSION_GOAL_REACHED: return "GOAL_REACHED";
    case msgs::MISSION_STOPPED_FAULT: return "STOPPED_FAULT";
    case msgs::MISSION_LINK_LOST: return "LINK_LOST";
  }
  return "?";
}
const char* Name(msgs::ComponentState s) {
  switch (s) {
    case msgs::COMPONENT_UNCONFIGURED: return "UNCONFIGURED";
    case msgs::COMPONENT_INACTIVE: return "INACTIVE";
    case msgs::COMPONENT_ACTIVE: return "ACTIVE";
    case msgs::COMPONENT_FINALIZED: return "FINALIZED";
  }
  return "?";
}
const char* Name(msgs::MotionMode m) {
  switch (m) {
    case msgs::MOTION_STOP: return "STOP";
    case msgs::MOTION_VELOCITY: return "VELOCITY";
    case msgs::MOTION_FOLLOW_HALLWAY: return "FOLLOW_HALLWAY";
  }
  return "?";
}
const char* Name(msgs::LocomotionState s) {
  switch (s) {
    case msgs::LOCOMOTION_STOPPED: return "STOPPED";
    case msgs::LOCOMOTION_VELOCITY: return "VELOCITY";
    case msgs::LOCOMOTION_NO_SCAN: return "NO_SCAN";
    case msgs::LOCOMOTION_FOLLOWING: return "FOLLOWING";
    case msgs::LOCOMOTION_STOPPING: return "STOPPING";
    case msgs::LOCOMOTION_TURNING: return "TURNING";
    case msgs::LOCOMOTION_OBSTACLE: return "OBSTACLE";
  }
  return "?";
}
const char* Name(msgs::SonarReadingState s) {
  switch (s) {
    case msgs::SONAR_VALID: return "VALID";
    case msgs::SONAR_NO_ECHO: return "NO_ECHO";
    case msgs::SONAR_OUT_OF_RANGE: return "OUT_OF_RANGE";
    case msgs::SONAR_OUTSIDE_FOOTPRINT: return "OUTSIDE_FOOTPRINT";
    case msgs::SONAR_MALFORMED: return "MALFORMED";
  }
  return "?";
}

json ToJson(const msgs::SonarEcho& m) {
  return {{"header", Header(m.header())},
          {"range_in", std::vector<float>(m.range_in().begin(), m.range_in().end())}};
}

json ToJson(const msgs::SonarScan& m) {
  json states = json::array();
  for (auto s : m.reading_state()) states.push_back(Name(s));
  return {{"header", Header(m.header())},
          {"range_in", std::vector<float>(m.range_in().begin(), m.range_in().end())},
          {"reading_state", states},
          {"valid_count", m.valid_count()}};
}

json ToJson(const msgs::Image& m) {
  // FNV-1a over the pixels: enough to tell frames apart without printing them.
  uint64_t hash = 1469598103934665603ull;
  for (uint8_t b : m.data()) hash = (hash ^ b) * 1099511628211ull;
  return {{"header", Header(m.header())}, {"width_px", m.width_px()},
          {"height_px", m.height_px()},   {"encoding", m.encoding()},
          {"step_bytes", m.step_bytes()}, {"data_bytes", m.data().size()},
          {"fnv1a", hash}};
}

json ToJson(const msgs::WheelCommand& m) {
  return {{"header", Header(m.header())},
          {"left_speed_ftps", m.left_speed_ftps()},
          {"right_speed_ftps", m.right_speed_ftps()}};
}

json ToJson(const msgs::EncoderReading& m) {
  return {{"header", Header(m.header())},
          {"left_travel_in", m.left_travel_in()},
          {"right_travel_in", m.right_travel_in()}};
}

json ToJson(const msgs::MotionCommand& m) {
  return {{"header", Header(m.header())},
          {"mode", Name(m.mode())},
          {"linear_speed_ftps", m.linear_speed_ftps()},
          {"angular_rate_radps", m.angular_rate_radps()}};
}

json ToJson(const msgs::MotionState& m) {
  return {{"header", Header(m.header())},
          {"mode", Name(m.mode())},
          {"state", Name(m.state())},
          {"travel_sign", m.travel_sign()},
          {"offset_valid", m.offset_valid()},
          {"lateral_offset_in", m.lateral_offset_in()},
          {"heading_valid", m.heading_valid()},
          {"heading_error_deg", m.heading_error_deg()},
          {"in_envelope", m.in_envelope()},
          {"commanded_speed_ftps", m.commanded_speed_ftps()},
          {"linear_speed_ftps", m.linear_speed_ftps()},
          {"angular_rate_radps", m.angular_rate_radps()},
          {"message", m.message()}};
}

json ToJson(const msgs::Odometry& m) {
  return {{"header", Header(m.header())},
          {"pose", Pose(m.pose())},
          {"distance_in", m.distance_in()},
          {"linear_speed_ftps", m.linear_speed_ftps()},
          {"angular_rate_radps", m.angular_rate_radps()}};
}

json ToJson(const msgs::LandmarkObservation& m) {
  return {{"header", Header(m.header())},
          {"door_class", Name(m.door_class())},
          {"width_in", m.width_in()},
          {"confidence", m.confidence()},
          {"left_jamb_px", m.left_jamb_px()},
          {"right_jamb_px", m.right_jamb_px()},
          {"range_in", m.range_in()},
          {"center_offset_in", m.center_offset_in()},
          {"look_angle_rad", m.look_angle_rad()},
          {"in_envelope", m.in_envelope()},
          {"odometry_distance_in", m.odometry_distance_in()},
          {"image_stamp_ns", m.image_stamp_ns()}};
}

json ToJson(const msgs::LocalizationPose& m) {
  return {{"header", Header(m.header())},
          {"status", Name(m.status())},
          {"candidate_count", m.candidate_count()},
          {"best", Hypothesis(m.best())},
          {"confidence", m.confidence()},
          {"edges_sensed", m.edges_sensed()},
          {"message", m.message()}};
}

json ToJson(const msgs::PoseHypotheses& m) {
  json list = json::array();
  for (const auto& h : m.hypotheses()) list.push_back(Hypothesis(h));
  return {{"header", Header(m.header())}, {"hypotheses", list}};
}

json ToJson(const msgs::StickRepMap& m) {
  json rings = json::array();
  for (const auto& r : m.rings()) {
    rings.push_back({{"ring_id", r.ring_id()}, {"closed", r.closed()}, {"edges", r.edges().size()}});
  }
  return {{"header", Header(m.header())}, {"name", m.name()}, {"rings", rings}};
}

json ToJson(const msgs::MissionGoal& m) {
  return {{"header", Header(m.header())}, {"goal_id", m.goal_id()}, {"target", m.target()}};
}

json ToJson(const msgs::MissionStatus& m) {
  return {{"header", Header(m.header())},
          {"state", Name(m.state())},
          {"goal_id", m.goal_id()},
          {"message", m.message()}};
}

json ToJson(const msgs::MissionGoalResult& m) {
  return {{"header", Header(m.header())}, {"goal_id", m.goal_id()}, {"target", m.target()},
          {"accepted", m.accepted()}, {"reason", m.reason()}};
}

json ToJson(const msgs::ComponentStatus& m) {
  return {{"header", Header(m.header())},         {"component_name", m.component_name()},
          {"state", Name(m.state())},            {"samples_in", m.samples_in()},
          {"samples_out", m.samples_out()},      {"samples_dropped", m.samples_dropped()},
          {"message", m.message()},              {"host", m.host()}};
}

json ToJson(const msgs::GroundTruth& m) {
  return {{"header", Header(m.header())},   {"pose", Pose(m.pose())},
          {"ring_id", m.ring_id()},         {"edge_index", m.edge_index()},
          {"offset_in", m.offset_in()},     {"distance_in", m.distance_in()},
          {"lateral_offset_in", m.lateral_offset_in()},
          {"heading_error_deg", m.heading_error_deg()},
          {"collisions", m.collisions()},
          {"forward_in_ring", m.forward_in_ring()}};
}

}  // namespace stickrep::console
