#include "runtime/participant.h"

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>

#include <fastdds/rtps/attributes/ServerAttributes.h>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>
#include <tinyxml2.h>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <typeinfo>
#include <stdexcept>

#include "common/input_error.h"

namespace stickrep::runtime {

namespace dds = eprosima::fastdds::dds;
using eprosima::fastrtps::Duration_t;
using eprosima::fastrtps::types::ReturnCode_t;

namespace {

// A shared-memory segment, and UDP socket buffers, that hold several 250 kB camera frames
// (the kernel caps the buffers at net.core.rmem_max / wmem_max: deploy/setup.sh raises them).
constexpr uint32_t kSharedMemorySegmentBytes = 4u << 20;
constexpr uint32_t kUdpSocketBufferBytes = 4u << 20;

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

std::string CheckProfileXml(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) {
    throw InputError(path, 0, "", "no such Fast DDS XML profile file");
  }
  tinyxml2::XMLDocument doc;
  if (doc.LoadFile(path.c_str()) != tinyxml2::XML_SUCCESS) {
    throw InputError(path, doc.ErrorLineNum(), "",
                     std::string("malformed XML: ") + doc.ErrorStr());
  }
  const tinyxml2::XMLElement* root = doc.RootElement();
  const std::string root_name = root == nullptr ? "" : root->Name();
  if (root_name != "dds" && root_name != "profiles") {
    throw InputError(path, 1, "",
                     "not a Fast DDS profile file (the root element must be <dds> or <profiles>)");
  }
  const tinyxml2::XMLElement* profiles =
      root_name == "dds" ? root->FirstChildElement("profiles") : root;
  for (const tinyxml2::XMLElement* p =
           profiles == nullptr ? nullptr : profiles->FirstChildElement("participant");
       p != nullptr; p = p->NextSiblingElement("participant")) {
    const char* is_default = p->Attribute("is_default_profile");
    const char* name = p->Attribute("profile_name");
    if (is_default != nullptr && std::string(is_default) == "true" && name != nullptr) {
      return name;
    }
  }
  return "";
}

namespace {

std::string JoinServers(const std::vector<std::string>& servers, const char* separator) {
  std::string out;
  for (const std::string& s : servers) out += (out.empty() ? "" : separator) + s;
  return out;
}

std::string PrefixText(const eprosima::fastrtps::rtps::GuidPrefix_t& prefix) {
  std::ostringstream s;
  s << prefix;
  return s.str();
}

std::string LocatorsText(const eprosima::fastdds::rtps::RemoteServerList_t& servers) {
  std::vector<std::string> out;
  for (const auto& server : servers) {
    for (const auto& l : server.metatrafficUnicastLocatorList) {
      out.push_back(eprosima::fastrtps::rtps::IPLocator::toIPv4string(l) + ":" +
                    std::to_string(l.port));
    }
  }
  return JoinServers(out, ",");
}

}  // namespace

dds::DomainParticipantQos Participant::LoadQos() {
  auto* factory = dds::DomainParticipantFactory::get_instance();
  // Without a file: Fast DDS's defaults, whatever another participant of this process loaded.
  dds::DomainParticipantQos pqos;
  if (!config_.profile_xml.empty()) {
    // Fast DDS 2.9 does not make a loaded file's default profile the factory's default, so
    // the default participant profile is found here and asked for by name.
    const std::string default_profile = CheckProfileXml(config_.profile_xml);
    if (factory->load_XML_profiles_file(config_.profile_xml) != ReturnCode_t::RETCODE_OK) {
      throw InputError(config_.profile_xml, 0, "",
                       "Fast DDS refused this XML profile file (its reason is logged above)");
    }
    const std::string name =
        config_.profile_name.empty() ? default_profile : config_.profile_name;
    if (!name.empty() &&
        factory->get_participant_qos_from_profile(name, pqos) != ReturnCode_t::RETCODE_OK) {
      throw InputError(config_.profile_xml, 0, name,
                       "no participant profile with this name in the XML file");
    }
  }
  auto& transport = pqos.transport();
  if (!config_.shared_memory && transport.use_builtin_transports) {
    transport.use_builtin_transports = false;
    if (transport.user_transports.empty()) {
      auto udp = std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>();
      udp->sendBufferSize = kUdpSocketBufferBytes;
      udp->receiveBufferSize = kUdpSocketBufferBytes;
      transport.user_transports.push_back(udp);
    }
  } else if (config_.shared_memory && !transport.use_builtin_transports) {
    // A profile that names its own transports: shared memory beside them, unless named.
    const bool named = std::any_of(
        transport.user_transports.begin(), transport.user_transports.end(), [](const auto& t) {
          return std::dynamic_pointer_cast<eprosima::fastdds::rtps::SharedMemTransportDescriptor>(
                     t) != nullptr;
        });
    if (!named) {
      auto shm = std::make_shared<eprosima::fastdds::rtps::SharedMemTransportDescriptor>();
      shm->segment_size(kSharedMemorySegmentBytes);
      transport.user_transports.insert(transport.user_transports.begin(), shm);
    }
  }
  auto& discovery = pqos.wire_protocol().builtin.discovery_config;
  if (config_.announcement_period_s > 0.0) {
    discovery.leaseDuration_announcementperiod = ToDuration(config_.announcement_period_s);
  }
  if (!config_.discovery_servers.empty()) {
    eprosima::fastdds::rtps::RemoteServerList_t servers;
    const std::string list = JoinServers(config_.discovery_servers, ";");
    if (!eprosima::fastdds::rtps::load_environment_server_info(list, servers)) {
      throw InputError("--discovery-server", 0, list,
                       "not a list of IPv4 discovery server addresses IP:PORT");
    }
    discovery.m_DiscoveryServers = servers;
    if (discovery.discoveryProtocol == eprosima::fastrtps::rtps::DiscoveryProtocol_t::SIMPLE) {
      discovery.discoveryProtocol = eprosima::fastrtps::rtps::DiscoveryProtocol_t::CLIENT;
    }
  }
  using Protocol = eprosima::fastrtps::rtps::DiscoveryProtocol_t;
  if (discovery.discoveryProtocol == Protocol::CLIENT ||
      discovery.discoveryProtocol == Protocol::SUPER_CLIENT) {
    if (config_.security.enabled()) {
      // A secured server's GUID prefix comes from its certificate.
      for (auto& server : discovery.m_DiscoveryServers) {
        server.guidPrefix = SecuredServerPrefix(config_.security, server.guidPrefix);
      }
    }
    std::vector<std::string> prefixes;
    for (const auto& server : discovery.m_DiscoveryServers) {
      prefixes.push_back(PrefixText(server.guidPrefix));
    }
    discovery_.SetServers(prefixes);
    servers_text_ = LocatorsText(discovery.m_DiscoveryServers);
  }
  if (config_.security.enabled()) {
    const bool simple = discovery.discoveryProtocol == Protocol::SIMPLE;
    ApplySecurity(config_.security, pqos,
                  simple ? DiscoveryKind::kSimple : DiscoveryKind::kDiscoveryServer);
  }
  return pqos;
}

Participant::Participant(const ParticipantConfig& config, QosCatalog catalog)
    : config_(config), catalog_(std::move(catalog)) {
  auto* factory = dds::DomainParticipantFactory::get_instance();
  dds::DomainParticipantQos pqos = LoadQos();
  pqos.name(config_.name);
  participant_ = factory->create_participant(config_.domain_id, pqos, &discovery_,
                                             dds::StatusMask::none());
  if (participant_ == nullptr) {
    throw std::runtime_error(
        "could not create a DDS participant on domain " + std::to_string(config_.domain_id) +
        (config_.security.enabled()
             ? " (the security plugins refused identity '" + config_.security.identity +
                   "' of " + config_.security.dir + ": their reason is logged above)"
             : ""));
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
    // Already registered: TypeSupport owns the first instance. A raw (serialized) support
    // and the real one of the same name cannot share a participant: samples of one would
    // be handed to the other.
    const bool same_kind = typeid(*t->second.get()) == typeid(*type);
    delete type;
    if (!same_kind) {
      throw std::logic_error("type " + type_name + " is registered in another form on this "
                             "participant (raw and typed endpoints of one type cannot mix)");
    }
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
  return CreateDataWriter(topic, type, listener, catalog_.ForTopic(topic));
}

dds::DataReader* Participant::CreateDataReader(const std::string& topic, dds::TopicDataType* type,
                                               dds::DataReaderListener* listener) {
  return CreateDataReader(topic, type, listener, catalog_.ForTopic(topic));
}

dds::DataWriter* Participant::CreateDataWriter(const std::string& topic, dds::TopicDataType* type,
                                               dds::DataWriterListener* listener,
                                               const QosProfile& profile) {
  dds::Topic* t = GetTopic(topic, type);
  dds::DataWriterQos qos = ToDataWriterQos(profile, publisher_->get_default_datawriter_qos());
  if (!config_.shared_memory) qos.data_sharing().off();
  dds::DataWriter* writer = publisher_->create_datawriter(t, qos, listener);
  if (writer == nullptr) {
    throw std::runtime_error("could not create a DDS writer on " + topic +
                             (config_.security.enabled()
                                  ? " (identity '" + config_.security.identity +
                                        "' may not publish it?)"
                                  : ""));
  }
  return writer;
}

dds::DataReader* Participant::CreateDataReader(const std::string& topic, dds::TopicDataType* type,
                                               dds::DataReaderListener* listener,
                                               const QosProfile& profile) {
  dds::Topic* t = GetTopic(topic, type);
  dds::DataReaderQos qos = ToDataReaderQos(profile, subscriber_->get_default_datareader_qos());
  if (!config_.shared_memory) qos.data_sharing().off();
  dds::DataReader* reader = subscriber_->create_datareader(t, qos, listener);
  if (reader == nullptr) {
    throw std::runtime_error("could not create a DDS reader on " + topic +
                             (config_.security.enabled()
                                  ? " (identity '" + config_.security.identity +
                                        "' may not subscribe to it?)"
                                  : ""));
  }
  return reader;
}

void Participant::DeleteDataWriter(dds::DataWriter* writer) {
  if (writer != nullptr) publisher_->delete_datawriter(writer);
}

void Participant::DeleteDataReader(dds::DataReader* reader) {
  if (reader != nullptr) subscriber_->delete_datareader(reader);
}

}  // namespace stickrep::runtime
