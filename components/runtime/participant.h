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

#include "runtime/qos_catalog.h"

namespace stickrep::runtime {

// How a process joins the DDS domain.
struct ParticipantConfig {
  int domain_id = 0;
  std::string name;
  // Optional Fast DDS XML file (transports, discovery server); empty for the defaults.
  std::string profile_xml;
  // Participant profile inside that file; empty for the file's default profile.
  std::string profile_name;
};

// Owns one DomainParticipant with one Publisher and one Subscriber, and creates topics and
// endpoints with the QoS that the catalog names for each topic. Not copyable; destroy it
// after every Writer and Reader made from it.
class Participant {
 public:
  // Throws InputError if the XML profile cannot be loaded, std::runtime_error if DDS fails.
  // `listener`, if given, hears of remote endpoints being discovered (the console).
  Participant(const ParticipantConfig& config, QosCatalog catalog,
              eprosima::fastdds::dds::DomainParticipantListener* listener = nullptr);
  ~Participant();
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;

  const QosCatalog& catalog() const { return catalog_; }
  const std::string& name() const { return config_.name; }
  int domain_id() const { return config_.domain_id; }
  eprosima::fastdds::dds::DomainParticipant* dds() { return participant_; }

  // Raw endpoint creation for the typed wrappers (endpoint.h).
  eprosima::fastdds::dds::DataWriter* CreateDataWriter(
      const std::string& topic, eprosima::fastdds::dds::TopicDataType* type,
      eprosima::fastdds::dds::DataWriterListener* listener);
  eprosima::fastdds::dds::DataReader* CreateDataReader(
      const std::string& topic, eprosima::fastdds::dds::TopicDataType* type,
      eprosima::fastdds::dds::DataReaderListener* listener);
  void DeleteDataWriter(eprosima::fastdds::dds::DataWriter* writer);
  void DeleteDataReader(eprosima::fastdds::dds::DataReader* reader);

 private:
  eprosima::fastdds::dds::Topic* GetTopic(const std::string& topic,
                                          eprosima::fastdds::dds::TopicDataType* type);

  ParticipantConfig config_;
  QosCatalog catalog_;
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
