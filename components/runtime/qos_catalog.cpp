#include "runtime/qos_catalog.h"

namespace stickrep::runtime {

const char* ToString(QosProfile::Reliability r) {
  return r == QosProfile::Reliability::kReliable ? "reliable" : "best_effort";
}
const char* ToString(QosProfile::Durability d) {
  return d == QosProfile::Durability::kTransientLocal ? "transient_local" : "volatile";
}
const char* ToString(QosProfile::PublishMode m) {
  return m == QosProfile::PublishMode::kAsynchronous ? "asynchronous" : "synchronous";
}
std::string HistoryText(const QosProfile& p) {
  return p.history_depth == 0 ? "keep_all" : "keep_last " + std::to_string(p.history_depth);
}

namespace {

template <typename Enum>
Enum ParseChoice(const StrictYaml& node, const std::string& key,
                 const std::vector<std::pair<std::string, Enum>>& choices) {
  const std::string text = node.Get<std::string>(key);
  std::string allowed;
  for (const auto& [name, value] : choices) {
    if (text == name) return value;
    allowed += (allowed.empty() ? "" : ", ") + name;
  }
  node.Fail(key, "'" + text + "' is not one of: " + allowed);
}

QosProfile ParseProfile(const std::string& name, const StrictYaml& node) {
  QosProfile p;
  p.name = name;
  p.reliability = ParseChoice<QosProfile::Reliability>(
      node, "reliability",
      {{"best_effort", QosProfile::Reliability::kBestEffort},
       {"reliable", QosProfile::Reliability::kReliable}});
  p.durability = ParseChoice<QosProfile::Durability>(
      node, "durability",
      {{"volatile", QosProfile::Durability::kVolatile},
       {"transient_local", QosProfile::Durability::kTransientLocal}});
  p.history_depth = node.Get<int>("history_depth", 0, 10000);
  p.deadline_s = node.Get<double>("deadline_s", 0.0, 3600.0, "s");
  p.liveliness_lease_s = node.Get<double>("liveliness_lease_s", 0.0, 3600.0, "s");
  p.publish_mode = ParseChoice<QosProfile::PublishMode>(
      node, "publish_mode",
      {{"synchronous", QosProfile::PublishMode::kSynchronous},
       {"asynchronous", QosProfile::PublishMode::kAsynchronous}});
  if (p.liveliness_lease_s > 0.0 && p.liveliness_lease_s < 0.1) {
    node.Fail("liveliness_lease_s", "a lease below 0.1 s would be lost to scheduling jitter");
  }
  node.Finish();
  return p;
}

}  // namespace

QosCatalog QosCatalog::Load(const StrictYaml& root) {
  QosCatalog catalog;
  catalog.file_ = root.file();
  const StrictYaml qos = root.Child("qos");
  const StrictYaml profiles = qos.Child("profiles");
  for (const std::string& name : profiles.Keys()) {
    catalog.profiles_[name] = ParseProfile(name, profiles.Child(name));
  }
  profiles.Finish();
  for (const StrictYaml& s : qos.Sequence("streams")) {
    StreamQos stream;
    stream.topic = s.Get<std::string>("topic");
    stream.profile = s.Get<std::string>("profile");
    stream.reason = s.Get<std::string>("reason");
    if (catalog.profiles_.count(stream.profile) == 0) {
      s.Fail("profile", "no QoS profile named '" + stream.profile + "' in qos.profiles");
    }
    if (stream.reason.size() < 10) s.Fail("reason", "say why this stream has this QoS");
    if (!catalog.streams_.emplace(stream.topic, stream).second) {
      s.Fail("topic", "topic '" + stream.topic + "' is listed twice");
    }
    s.Finish();
  }
  qos.Finish();
  root.Finish();
  return catalog;
}

QosCatalog QosCatalog::LoadFile(const std::string& path) {
  return Load(StrictYaml::LoadFile(path));
}

const QosProfile& QosCatalog::ForTopic(const std::string& topic) const {
  const auto it = streams_.find(topic);
  if (it == streams_.end()) {
    throw InputError(file_, 0, "qos.streams",
                     "no QoS choice for topic '" + topic + "': add it to the streams list");
  }
  return profiles_.at(it->second.profile);
}

const QosProfile& QosCatalog::Profile(const std::string& name) const {
  const auto it = profiles_.find(name);
  if (it == profiles_.end()) {
    throw InputError(file_, 0, "qos.profiles", "no QoS profile named '" + name + "'");
  }
  return it->second;
}

}  // namespace stickrep::runtime
