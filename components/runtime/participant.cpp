#include "runtime/participant.h"

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>

#include <stdexcept>

#include "common/input_error.h"

namespace stickrep::runtime {

namespace dds = eprosima::fastdds::dds;
using eprosima::fastrtps::Duration_t;
using eprosima::fastrtps::types::ReturnCode_t;

namespace {

Duration_t ToDuration(double seconds) {
  if (seconds <= 0.0) return eprosima::fastrtps::c_TimeInfinite;
  const auto sec = static_cast<int32_t>(seconds);
  const auto nsec = static_cast<uint32_t>((seconds - sec) * 1e9);
  return Duration_t(sec, nsec);
}

template <typename EndpointQos>
void ApplyCommon(const QosProfile& p, EndpointQos& q) {
  q.reliability().kind = p.reliability == QosProfile::Reliability::kReliable
                             ? dds::RELIABLE_RELIABILITY_QOS
                             : dds::BEST_EFFORT_RELIABILITY_QOS;
  q.durability().kind = p.durability == QosProfile::Durability::kTransientLocal
                            ? dds::TRANSIENT_LOCAL_DURABILITY_QOS
                            : dds::VOLATILE_DURABILITY_QOS;
  if (p.history_depth == 0) {
    q.history().kind = dds::KEEP_ALL_HISTORY_QOS;
  } else {
    q.history().kind = dds::KEEP_LAST_HISTORY_QOS;
    q.history().depth = p.history_depth;
  }
  q.deadline().period = ToDuration(p.deadline_s);
  q.liveliness().kind = dds::AUTOMATIC_LIVELINESS_QOS;
  q.liveliness().lease_duration = ToDuration(p.liveliness_lease_s);
  if (p.liveliness_lease_s > 0.0) {
    q.liveliness().announcement_period = ToDuration(p.liveliness_lease_s / 3.0);
  }
}

}  // namespace

std::string EncodeProfileUserData(const QosProfile& p) {
  return "stickrep;profile=" + p.name + ";history=" + HistoryText(p) +
         ";publish_mode=" + ToString(p.publish_mode);
}

dds::DataWriterQos ToDataWriterQos(const QosProfile& p, dds::DataWriterQos q) {
  ApplyCommon(p, q);
  q.publish_mode().kind = p.publish_mode == QosProfile::PublishMode::kAsynchronous
                              ? dds::ASYNCHRONOUS_PUBLISH_MODE
                              : dds::SYNCHRONOUS_PUBLISH_MODE;
  const std::string text = EncodeProfileUserData(p);
  q.user_data().data_vec(std::vector<eprosima::fastrtps::rtps::octet>(text.begin(), text.end()));
  return q;
}

dds::DataReaderQos ToDataReaderQos(const QosProfile& p, dds::DataReaderQos q) {
  ApplyCommon(p, q);
  const std::string text = EncodeProfileUserData(p);
  q.user_data().data_vec(std::vector<eprosima::fastrtps::rtps::octet>(text.begin(), text.end()));
  return q;
}

Participant::Participant(const ParticipantConfig& config, QosCatalog catalog,
                         dds::DomainParticipantListener* listener)
    : config_(config), catalog_(std::move(catalog)) {
  auto* factory = dds::DomainParticipantFactory::get_instance();
  if (!config_.profile_xml.empty()) {
    if (factory->load_XML_profiles_file(config_.profile_xml) != ReturnCode_t::RETCODE_OK) {
      throw InputError(config_.profile_xml, 0, "",
                       "Fast DDS could not load this XML profile file");
    }
  }
  dds::DomainParticipantQos pqos;
  if (!config_.profile_xml.empty() && !config_.profile_name.empty()) {
    if (factory->get_participant_qos_from_profile(config_.profile_name, pqos) !=
        ReturnCode_t::RETCODE_OK) {
      throw InputError(config_.profile_xml, 0, config_.profile_name,
                       "no participant profile with this name in the XML file");
    }
  } else {
    pqos = factory->get_default_participant_qos();  // the XML default profile, if any
  }
  pqos.name(config_.name);
  participant_ = factory->create_participant(config_.domain_id, pqos, listener,
                                             dds::StatusMask::none());
  if (participant_ == nullptr) {
    throw std::runtime_error("could not create a DDS participant on domain " +
                             std::to_string(config_.domain_id));
  }
  publisher_ = participant_->create_publisher(dds::PUBLISHER_QOS_DEFAULT);
  subscriber_ = participant_->create_subscriber(dds::SUBSCRIBER_QOS_DEFAULT);
  if (publisher_ == nullptr || subscriber_ == nullptr) {
    throw std::runtime_error("could not create the DDS publisher or subscriber");
  }
}

Participant::~Participant() {
  if (participant_ != nullptr) {
    participant_->delete_contained_entities();
    dds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
  }
}

dds::Topic* Participant::GetTopic(const std::string& topic, dds::TopicDataType* type) {
  std::lock_guard<std::mutex> lock(mutex_);
  const std::string type_name = type->getName();
  auto t = types_.find(type_name);
  if (t == types_.end()) {
    dds::TypeSupport support(type);
    if (support.register_type(participant_) != ReturnCode_t::RETCODE_OK) {
      throw std::runtime_error("could not register DDS type " + type_name);
    }
    types_.emplace(type_name, support);
  } else {
    delete type;  // already registered: TypeSupport owns the first instance
  }
  auto it = topics_.find(topic);
  if (it != topics_.end()) return it->second;
  dds::Topic* created = participant_->create_topic(topic, type_name, dds::TOPIC_QOS_DEFAULT);
  if (created == nullptr) throw std::runtime_error("could not create DDS topic " + topic);
  topics_.emplace(topic, created);
  return created;
}

dds::DataWriter* Participant::CreateDataWriter(const std::string& topic, dds::TopicDataType* type,
                                               dds::DataWriterListener* listener) {
  const QosProfile& profile = catalog_.ForTopic(topic);
  dds::Topic* t = GetTopic(topic, type);
  dds::DataWriter* writer = publisher_->create_datawriter(
      t, ToDataWriterQos(profile, publisher_->get_default_datawriter_qos()), listener);
  if (writer == nullptr) throw std::runtime_error("could not create a DDS writer on " + topic);
  return writer;
}

dds::DataReader* Participant::CreateDataReader(const std::string& topic, dds::TopicDataType* type,
                                               dds::DataReaderListener* listener) {
  const QosProfile& profile = catalog_.ForTopic(topic);
  dds::Topic* t = GetTopic(topic, type);
  dds::DataReader* reader = subscriber_->create_datareader(
      t, ToDataReaderQos(profile, subscriber_->get_default_datareader_qos()), listener);
  if (reader == nullptr) throw std::runtime_error("could not create a DDS reader on " + topic);
  return reader;
}

void Participant::DeleteDataWriter(dds::DataWriter* writer) {
  if (writer != nullptr) publisher_->delete_datawriter(writer);
}

void Participant::DeleteDataReader(dds::DataReader* reader) {
  if (reader != nullptr) subscriber_->delete_datareader(reader);
}

}  // namespace stickrep::runtime
