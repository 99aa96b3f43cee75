#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <fastdds/dds/domain/DomainParticipantListener.hpp>

namespace stickrep::runtime {

// One endpoint seen on the domain through DDS discovery.
struct DiscoveredEndpoint {
  std::string topic;
  std::string type;
  bool is_writer = false;
  std::string reliability;       // "reliable" / "best_effort"
  std::string durability;        // "volatile" / "transient_local" / ...
  double deadline_s = 0.0;       // 0: none
  double liveliness_lease_s = 0; // 0: infinite
  std::string user_data;         // StickRep endpoints carry their profile and history here
  std::string guid;              // the endpoint's DDS GUID, as text
  std::string participant;       // its participant's name ("stickrep-landmark"), "" if unknown
};

// Everything known of one topic, summed over its endpoints.
struct TopicSummary {
  std::string topic;
  std::string type;
  int writers = 0;
  int readers = 0;
  std::string reliability;
  std::string durability;
  std::string history;           // from the endpoints' user_data ("keep_last 5"), or "?"
  double deadline_s = 0.0;
  double liveliness_lease_s = 0.0;
  std::string profile;
  bool mixed_qos = false;        // endpoints disagree on reliability or durability
};

// Listens to DDS discovery and keeps the set of remote participants, writers and readers.
// Every Participant owns one; the console reads it to show what is on the domain.
class DiscoveryListener : public eprosima::fastdds::dds::DomainParticipantListener {
 public:
  // The discovery servers this participant is a client of (GUID prefixes as text), so that
  // reaching and losing them can be told.
  void SetServers(std::vector<std::string> server_prefixes);
  void on_participant_discovery(eprosima::fastdds::dds::DomainParticipant*,
                                eprosima::fastrtps::rtps::ParticipantDiscoveryInfo&& info) override;
  void on_publisher_discovery(eprosima::fastdds::dds::DomainParticipant*,
                              eprosima::fastrtps::rtps::WriterDiscoveryInfo&& info) override;
  void on_subscriber_discovery(eprosima::fastdds::dds::DomainParticipant*,
                               eprosima::fastrtps::rtps::ReaderDiscoveryInfo&& info) override;
  // DDS Security: a remote participant authenticated, or refused (its GUID kept).
  void onParticipantAuthentication(
      eprosima::fastdds::dds::DomainParticipant*,
      eprosima::fastrtps::rtps::ParticipantAuthenticationInfo&& info) override;
  int Authenticated() const;
  // The GUID prefixes of the participants authenticated so far, in order.
  std::vector<std::string> AuthenticatedPrefixes() const;
  // A participant's name from its GUID prefix ("" if not discovered).
  std::string NameOf(const std::string& prefix) const;
  std::vector<std::string> Refused() const;
  std::vector<DiscoveredEndpoint> Endpoints() const;
  // Names of the remote participants alive now.
  std::vector<std::string> Participants() const;
  bool UsesServers() const;
  // How many of the configured discovery servers are discovered now.
  int ServersReached() const;

 private:
  mutable std::mutex mutex_;
  std::map<std::string, DiscoveredEndpoint> by_guid_;
  std::map<std::string, std::string> participants_;  // GUID prefix -> name
  std::vector<std::string> servers_;
  std::vector<std::string> authenticated_prefixes_;
  std::vector<std::string> refused_;
};

// Folds endpoints into one summary per topic, sorted by topic name.
std::vector<TopicSummary> Summarise(const std::vector<DiscoveredEndpoint>& endpoints);

// Reads "key=value" from a StickRep user_data text; empty if absent.
// A GUID as Fast DDS prints it ("01.0f.....|0.0.1.3"): the key of DiscoveredEndpoint::guid.
std::string GuidText(const eprosima::fastrtps::rtps::GUID_t& guid);

std::string UserDataField(const std::string& user_data, const std::string& key);

}  // namespace stickrep::runtime
