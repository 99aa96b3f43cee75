#pragma once

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "runtime/discovery.h"
#include "runtime/qos_catalog.h"
#include "runtime/security.h"

namespace stickrep::runtime {

// How a process joins the DDS domain.
struct ParticipantConfig {
  int domain_id = 0;
  std::string name;
  // Optional Fast DDS XML file (transports, discovery server); empty for the defaults.
  std::string profile_xml;
  // Participant profile inside that file; empty for the file's default profile.
  std::string profile_name;
  // Discovery servers ("IP:PORT", the i-th with the GUID prefix of `fast-discovery-server
  // -i i`). Given, they replace the profile's server list, and a participant whose profile
  // uses simple (multicast) discovery becomes a discovery-server client.
  std::vector<std::string> discovery_servers;
  // How often the participant announces itself (simple discovery); 0: Fast DDS's 3 s. A
  // participant that joins a running domain and must be found at once (the recorder) uses
  // a short period: a participant that appears later learns of it within that time.
  double announcement_period_s = 0.0;
  // Shared memory beside UDP, as Fast DDS has it by default. Off unless asked for
  // (system.shared_memory), for two faults of Fast DDS 2.9's shared-memory transport:
  // - a process killed and restarted on the same host reopens its dead predecessor's port
  //   as a new segment while the other processes keep writing into the old one, so the new
  //   process misses them for good (eProsima/Fast-DDS#4728): 15 of 25 executives killed
  //   and restarted in a row never heard some or all of the processes they wait for;
  // - a stopped observer's full port held every writing process up for seconds, where a
  //   full UDP socket only loses that observer's samples.
  // A profile that names its own transports keeps them. Off also turns off data sharing
  // (Fast DDS's shared-memory delivery between the writers and readers of one host, used by
  // default for plain types such as robot/odometry): a reader SIGKILLed while it held its
  // notification mutex made the writer's next write wait 1 s on the dead owner and throw,
  // and locomotion ended ("Interprocess mutex timeout when locking").
  bool shared_memory = false;
  // DDS Security (authentication, access control, encryption); off when its dir is empty.
  SecurityConfig security = {};
};

// Checks that a Fast DDS XML profile file exists and is well-formed XML; throws InputError
// naming the file, the line and the parser's reason. Returns the name of the file's default
// participant profile (is_default_profile="true"), or "" if it has none.
std::string CheckProfileXml(const std::string& path);

// Owns one DomainParticipant with one Publisher and one Subscriber, and creates topics and
// endpoints with the QoS that the catalog names for each topic. Not copyable; destroy it
// after every Writer and Reader made from it.
class Participant {
 public:
  // Throws InputError if the XML profile cannot be loaded or a server address is malformed,
  // std::runtime_error if DDS fails.
  Participant(const ParticipantConfig& config, QosCatalog catalog);
  ~Participant();
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;

  const QosCatalog& catalog() const { return catalog_; }
  const std::string& name() const { return config_.name; }
  int domain_id() const { return config_.domain_id; }
  // The DDS Security identity it authenticates as; "" when not secured.
  const std::string& security_identity() const { return config_.security.identity; }
  eprosima::fastdds::dds::DomainParticipant* dds() { return participant_; }
  // What discovery has found: remote participants, writers and readers, servers reached.
  const DiscoveryListener& discovery() const { return discovery_; }
  // The discovery servers in use, as text for messages ("10.0.0.1:11811"); empty when the
  // participant uses simple (multicast) discovery.
  const std::string& servers_text() const { return servers_text_; }

  // Raw endpoint creation for the typed wrappers (endpoint.h).
  eprosima::fastdds::dds::DataWriter* CreateDataWriter(
      const std::string& topic, eprosima::fastdds::dds::TopicDataType* type,
      eprosima::fastdds::dds::DataWriterListener* listener);
  eprosima::fastdds::dds::DataReader* CreateDataReader(
      const std::string& topic, eprosima::fastdds::dds::TopicDataType* type,
      eprosima::fastdds::dds::DataReaderListener* listener);
  // The same with an explicit profile instead of the catalogue's (recorder, replayer).
  eprosima::fastdds::dds::DataWriter* CreateDataWriter(
      const std::string& topic, eprosima::fastdds::dds::TopicDataType* type,
      eprosima::fastdds::dds::DataWriterListener* listener, const QosProfile& profile);
  eprosima::fastdds::dds::DataReader* CreateDataReader(
      const std::string& topic, eprosima::fastdds::dds::TopicDataType* type,
      eprosima::fastdds::dds::DataReaderListener* listener, const QosProfile& profile);
  void DeleteDataWriter(eprosima::fastdds::dds::DataWriter* writer);
  void DeleteDataReader(eprosima::fastdds::dds::DataReader* reader);

 private:
  eprosima::fastdds::dds::Topic* GetTopic(const std::string& topic,
                                          eprosima::fastdds::dds::TopicDataType* type);

  eprosima::fastdds::dds::DomainParticipantQos LoadQos();

  ParticipantConfig config_;
  QosCatalog catalog_;
  DiscoveryListener discovery_;
  std::string servers_text_;
  eprosima::fastdds::dds::DomainParticipant* participant_ = nullptr;
  eprosima::fastdds::dds::Publisher* publisher_ = nullptr;
  eprosima::fastdds::dds::Subscriber* subscriber_ = nullptr;
  std::mutex mutex_;
  std::map<std::string, eprosima::fastdds::dds::TypeSupport> types_;
  std::map<std::string, eprosima::fastdds::dds::Topic*> topics_;
};

// The QoS objects for a profile. The writer's user_data carries the profile in text
// ("stickrep;profile=NAME;history=keep_last 5;publish_mode=synchronous") because DDS
// discovery does not carry history or publish mode and the console shows them.
eprosima::fastdds::dds::DataWriterQos ToDataWriterQos(const QosProfile& p,
                                                     eprosima::fastdds::dds::DataWriterQos base);
eprosima::fastdds::dds::DataReaderQos ToDataReaderQos(const QosProfile& p,
                                                     eprosima::fastdds::dds::DataReaderQos base);
std::string EncodeProfileUserData(const QosProfile& p);

}  // namespace stickrep::runtime
