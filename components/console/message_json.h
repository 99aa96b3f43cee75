#pragma once

#include <nlohmann/json.hpp>

#include "basePubSubTypes.h"
#include "localizationPubSubTypes.h"
#include "missionPubSubTypes.h"
#include "perceptionPubSubTypes.h"
#include "sensorsPubSubTypes.h"
#include "systemPubSubTypes.h"

namespace stickrep::console {

// One JSON object per StickRep sample, for `stickrep-console echo`. Images print their
// shape and a checksum instead of the pixels.
nlohmann::json ToJson(const msgs::SonarEcho& m);
nlohmann::json ToJson(const msgs::SonarScan& m);
nlohmann::json ToJson(const msgs::Image& m);
nlohmann::json ToJson(const msgs::WheelCommand& m);
nlohmann::json ToJson(const msgs::EncoderReading& m);
nlohmann::json ToJson(const msgs::MotionCommand& m);
nlohmann::json ToJson(const msgs::MotionState& m);
nlohmann::json ToJson(const msgs::Odometry& m);
nlohmann::json ToJson(const msgs::LandmarkObservation& m);
nlohmann::json ToJson(const msgs::LocalizationPose& m);
nlohmann::json ToJson(const msgs::PoseHypotheses& m);
nlohmann::json ToJson(const msgs::StickRepMap& m);
nlohmann::json ToJson(const msgs::MissionGoal& m);
nlohmann::json ToJson(const msgs::MissionStatus& m);
nlohmann::json ToJson(const msgs::MissionGoalResult& m);
nlohmann::json ToJson(const msgs::ComponentStatus& m);
nlohmann::json ToJson(const msgs::GroundTruth& m);

// Enum names as the IDL spells them.
const char* Name(msgs::DoorClass c);
const char* Name(msgs::LocalizationStatus s);
const char* Name(msgs::MissionState s);
const char* Name(msgs::ComponentState s);
const char* Name(msgs::MotionMode m);
const char* Name(msgs::SonarReadingState s);

}  // namespace stickrep::console
