#pragma once

#include <map>
#include <string>
#include <vector>

#include "common/strict_yaml.h"

namespace stickrep::runtime {

// A named set of QoS choices, written once in configs/qos.yaml and used by every writer and
// reader of a stream (navigation2's qos_profiles.hpp, but as data). Plain values: the
// conversion to Fast DDS QoS objects lives in participant.cpp.
struct QosProfile {
  enum class Reliability { kBestEffort, kReliable };
  enum class Durability { kVolatile, kTransientLocal };
  enum class PublishMode { kSynchronous, kAsynchronous };

  std::string name;
  Reliability reliability = Reliability::kReliable;
  Durability durability = Durability::kVolatile;
  int history_depth = 1;           // KEEP_LAST depth; 0 means KEEP_ALL
  double deadline_s = 0.0;         // 0: no deadline
  double liveliness_lease_s = 0.0; // 0: infinite lease (no liveliness check)
  PublishMode publish_mode = PublishMode::kSynchronous;
};

const char* ToString(QosProfile::Reliability r);
const char* ToString(QosProfile::Durability d);
const char* ToString(QosProfile::PublishMode m);
// "keep_last 5" or "keep_all".
std::string HistoryText(const QosProfile& p);

// The QoS choice of one topic and why it was chosen.
struct StreamQos {
  std::string topic;
  std::string profile;
  std::string reason;
};

// Every stream's QoS, from one file. Unknown profile names and topics without a choice are
// errors at set-up, never silently defaulted.
class QosCatalog {
 public:
  // Reads the `qos:` key of a document (configs/qos.yaml). Throws InputError.
  static QosCatalog Load(const StrictYaml& root);
  static QosCatalog LoadFile(const std::string& path);

  // The profile for a topic; throws InputError naming the file if the topic has no entry.
  const QosProfile& ForTopic(const std::string& topic) const;
  // The profile by name; throws InputError if there is none.
  const QosProfile& Profile(const std::string& name) const;
  bool HasTopic(const std::string& topic) const { return streams_.count(topic) > 0; }
  const std::map<std::string, StreamQos>& streams() const { return streams_; }
  const std::map<std::string, QosProfile>& profiles() const { return profiles_; }
  const std::string& file() const { return file_; }

 private:
  std::string file_;
  std::map<std::string, QosProfile> profiles_;
  std::map<std::string, StreamQos> streams_;
};

}  // namespace stickrep::runtime
