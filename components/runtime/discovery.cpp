#include "runtime/discovery.h"

#include <fastdds/rtps/builtin/data/ReaderProxyData.h>
#include <fastdds/rtps/builtin/data/WriterProxyData.h>

#include <sstream>

namespace stickrep::runtime {

namespace dds = eprosima::fastdds::dds;

std::string GuidText(const eprosima::fastrtps::rtps::GUID_t& guid) {
  std::ostringstream s;
  s << guid;
  return s.str();
}

namespace {

double Seconds(const eprosima::fastrtps::Duration_t& d) {
  if (d == eprosima::fastrtps::c_TimeInfinite) return 0.0;
  return d.seconds + d.nanosec * 1e-9;
}

template <typename Qos>
void FillQos(const Qos& q, DiscoveredEndpoint& e) {
  e.reliability = q.m_reliability.kind == dds::RELIABLE_RELIABILITY_QOS ? "reliable" : "best_effort";
  switch (q.m_durability.kind) {
    case dds::VOLATILE_DURABILITY_QOS: e.durability = "volatile"; break;
    case dds::TRANSIENT_LOCAL_DURABILITY_QOS: e.durability = "transient_local"; break;
    case dds::TRANSIENT_DURABILITY_QOS: e.durability = "transient"; break;
    case dds::PERSISTENT_DURABILITY_QOS: e.durability = "persistent"; break;
  }
  e.deadline_s = Seconds(q.m_deadline.period);
  e.liveliness_lease_s = Seconds(q.m_liveliness.lease_duration);
  const auto& data = q.m_userData.data_vec();
  e.user_data.assign(data.begin(), data.end());
}

}  // namespace

void DiscoveryListener::on_publisher_discovery(dds::DomainParticipant*,
                                               eprosima::fastrtps::rtps::WriterDiscoveryInfo&& info) {
  const std::string guid = GuidText(info.info.guid());
  std::lock_guard<std::mutex> lock(mutex_);
  if (info.status == eprosima::fastrtps::rtps::WriterDiscoveryInfo::REMOVED_WRITER) {
    by_guid_.erase(guid);
    return;
  }
  DiscoveredEndpoint e;
  e.topic = info.info.topicName().to_string();
  e.type = info.info.typeName().to_string();
  e.is_writer = true;
  e.guid = guid;
  FillQos(info.info.m_qos, e);
  by_guid_[guid] = e;
}

void DiscoveryListener::on_subscriber_discovery(dds::DomainParticipant*,
                                                eprosima::fastrtps::rtps::ReaderDiscoveryInfo&& info) {
  const std::string guid = GuidText(info.info.guid());
  std::lock_guard<std::mutex> lock(mutex_);
  if (info.status == eprosima::fastrtps::rtps::ReaderDiscoveryInfo::REMOVED_READER) {
    by_guid_.erase(guid);
    return;
  }
  DiscoveredEndpoint e;
  e.topic = info.info.topicName().to_string();
  e.type = info.info.typeName().to_string();
  e.is_writer = false;
  e.guid = guid;
  FillQos(info.info.m_qos, e);
  by_guid_[guid] = e;
}

void DiscoveryListener::SetServers(std::vector<std::string> server_prefixes) {
  std::lock_guard<std::mutex> lock(mutex_);
  servers_ = std::move(server_prefixes);
}

void DiscoveryListener::on_participant_discovery(
    dds::DomainParticipant*, eprosima::fastrtps::rtps::ParticipantDiscoveryInfo&& info) {
  using Info = eprosima::fastrtps::rtps::ParticipantDiscoveryInfo;
  std::ostringstream prefix;
  prefix << info.info.m_guid.guidPrefix;
  std::lock_guard<std::mutex> lock(mutex_);
  switch (info.status) {
    case Info::DISCOVERED_PARTICIPANT:
    case Info::CHANGED_QOS_PARTICIPANT:
      participants_[prefix.str()] = info.info.m_participantName.to_string();
      break;
    default:  // removed, dropped or ignored
      participants_.erase(prefix.str());
      break;
  }
}

void DiscoveryListener::onParticipantAuthentication(
    dds::DomainParticipant*, eprosima::fastrtps::rtps::ParticipantAuthenticationInfo&& info) {
  using Info = eprosima::fastrtps::rtps::ParticipantAuthenticationInfo;
  std::ostringstream prefix;
  prefix << info.guid.guidPrefix;
  std::lock_guard<std::mutex> lock(mutex_);
  if (info.status == Info::AUTHORIZED_PARTICIPANT) {
    authenticated_prefixes_.push_back(prefix.str());
  } else {
    refused_.push_back(prefix.str());
  }
}

std::vector<std::string> DiscoveryListener::AuthenticatedPrefixes() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return authenticated_prefixes_;
}

std::string DiscoveryListener::NameOf(const std::string& prefix) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = participants_.find(prefix);
  return it == participants_.end() ? "" : it->second;
}

int DiscoveryListener::Authenticated() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return static_cast<int>(authenticated_prefixes_.size());
}

std::vector<std::string> DiscoveryListener::Refused() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return refused_;
}

std::vector<std::string> DiscoveryListener::Participants() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<std::string> out;
  for (const auto& [prefix, name] : participants_) out.push_back(name);
  return out;
}

bool DiscoveryListener::UsesServers() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return !servers_.empty();
}

int DiscoveryListener::ServersReached() const {
  std::lock_guard<std::mutex> lock(mutex_);
  int n = 0;
  for (const std::string& s : servers_) n += participants_.count(s) > 0 ? 1 : 0;
  return n;
}

std::vector<DiscoveredEndpoint> DiscoveryListener::Endpoints() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<DiscoveredEndpoint> out;
  for (const auto& [guid, e] : by_guid_) {
    out.push_back(e);
    // The GUID's first 12 bytes are the participant's prefix ("01.0f.....|0.0.1.3").
    const auto bar = guid.find('|');
    const auto p = participants_.find(guid.substr(0, bar));
    if (p != participants_.end()) out.back().participant = p->second;
  }
  return out;
}

std::string UserDataField(const std::string& user_data, const std::string& key) {
  std::istringstream in(user_data);
  std::string part;
  while (std::getline(in, part, ';')) {
    const auto eq = part.find('=');
    if (eq != std::string::npos && part.substr(0, eq) == key) return part.substr(eq + 1);
  }
  return "";
}

std::vector<TopicSummary> Summarise(const std::vector<DiscoveredEndpoint>& endpoints) {
  std::map<std::string, TopicSummary> topics;
  for (const DiscoveredEndpoint& e : endpoints) {
    auto [it, fresh] = topics.try_emplace(e.topic);
    TopicSummary& t = it->second;
    if (fresh) {
      t.topic = e.topic;
      t.type = e.type;
      t.history = "?";
    }
    (e.is_writer ? t.writers : t.readers)++;
    // A writer's offer describes the stream; a reader-only topic shows the readers' request.
    if (e.is_writer || t.writers == 0) {
      if (!t.reliability.empty() && (t.reliability != e.reliability || t.durability != e.durability)) {
        t.mixed_qos = true;
      }
      t.reliability = e.reliability;
      t.durability = e.durability;
      t.deadline_s = e.deadline_s;
      t.liveliness_lease_s = e.liveliness_lease_s;
      const std::string history = UserDataField(e.user_data, "history");
      if (!history.empty()) t.history = history;
      const std::string profile = UserDataField(e.user_data, "profile");
      if (!profile.empty()) t.profile = profile;
    }
  }
  std::vector<TopicSummary> out;
  for (auto& [name, t] : topics) out.push_back(std::move(t));
  return out;
}

}  // namespace stickrep::runtime
