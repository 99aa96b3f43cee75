#include "console/message_types.h"

#include <fastdds/rtps/common/SerializedPayload.h>

#include <algorithm>
#include <cstring>
#include <new>

#include "basePubSubTypes.h"
#include "localizationPubSubTypes.h"
#include "missionPubSubTypes.h"
#include "msgs_json.h"
#include "perceptionPubSubTypes.h"
#include "sensorsPubSubTypes.h"
#include "systemPubSubTypes.h"

namespace stickrep::console {

namespace {

// Deserializes a raw payload with the type's own support class; its JSON form (msgs_json.h).
template <typename PubSubType>
nlohmann::json Decode(const std::uint8_t* data, std::size_t size) {
  if (size < 4) throw PayloadError("payload of " + std::to_string(size) + " bytes: no CDR header");
  eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<uint32_t>(size));
  std::memcpy(payload.data, data, size);
  payload.length = static_cast<uint32_t>(size);
  PubSubType support;
  typename PubSubType::type sample;
  bool ok = false;
  try {
    ok = support.deserialize(&payload, &sample);
  } catch (const std::bad_alloc&) {
    throw PayloadError("a sequence length in the payload exceeds memory");
  } catch (const std::exception& e) {
    throw PayloadError(std::string("CDR: ") + e.what());
  }
  if (!ok) throw PayloadError(std::string("the payload does not deserialize to ") + support.getName());
  return nlohmann::json(sample);
}

template <typename PubSubType>
MessageType Entry(const char* name, std::vector<std::string> topics) {
  return MessageType{name, std::move(topics), [] { return new PubSubType(); },
                     &Decode<PubSubType>};
}

}  // namespace

const std::map<std::string, MessageType>& MessageTypes() {
  static const std::map<std::string, MessageType> types = [] {
    std::map<std::string, MessageType> t;
    for (MessageType m : {
             Entry<msgs::SonarEchoPubSubType>("stickrep::msgs::SonarEcho", {"device/sonar/echo"}),
             Entry<msgs::SonarScanPubSubType>("stickrep::msgs::SonarScan", {"robot/sonar"}),
             Entry<msgs::ImagePubSubType>("stickrep::msgs::Image", {"device/camera/frame", "robot/camera/image"}),
             Entry<msgs::WheelCommandPubSubType>("stickrep::msgs::WheelCommand", {"device/base/wheel_command"}),
             Entry<msgs::EncoderReadingPubSubType>("stickrep::msgs::EncoderReading", {"device/base/encoders"}),
             Entry<msgs::MotionCommandPubSubType>("stickrep::msgs::MotionCommand", {"robot/motion/command"}),
             Entry<msgs::MotionStatePubSubType>("stickrep::msgs::MotionState", {"robot/motion/state"}),
             Entry<msgs::OdometryPubSubType>("stickrep::msgs::Odometry", {"robot/odometry"}),
             Entry<msgs::LandmarkObservationPubSubType>("stickrep::msgs::LandmarkObservation", {"perception/landmark"}),
             Entry<msgs::LocalizationPosePubSubType>("stickrep::msgs::LocalizationPose", {"localization/pose"}),
             Entry<msgs::PoseHypothesesPubSubType>("stickrep::msgs::PoseHypotheses", {"localization/hypotheses"}),
             Entry<msgs::StickRepMapPubSubType>("stickrep::msgs::StickRepMap", {"map/stickrep"}),
             Entry<msgs::MissionGoalPubSubType>("stickrep::msgs::MissionGoal", {"mission/goal"}),
             Entry<msgs::MissionGoalResultPubSubType>("stickrep::msgs::MissionGoalResult",
                                                      {"mission/goal_result"}),
             Entry<msgs::MissionStatusPubSubType>("stickrep::msgs::MissionStatus", {"mission/status"}),
             Entry<msgs::ComponentStatusPubSubType>("stickrep::msgs::ComponentStatus", {"system/status"}),
             Entry<msgs::GroundTruthPubSubType>("stickrep::msgs::GroundTruth", {"sim/ground_truth"}),
         }) {
      t.emplace(m.name, std::move(m));
    }
    return t;
  }();
  return types;
}

const MessageType* TypeOfTopic(const std::string& topic) {
  for (const auto& [name, type] : MessageTypes()) {
    if (std::find(type.topics.begin(), type.topics.end(), topic) != type.topics.end()) {
      return &type;
    }
  }
  return nullptr;
}

const MessageType* FindMessageType(const std::string& name) {
  const auto it = MessageTypes().find(name);
  return it == MessageTypes().end() ? nullptr : &it->second;
}

}  // namespace stickrep::console
