#include "runtime/bench/bench_link.h"

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fmt/format.h>

#include <atomic>
#include <stdexcept>
#include <thread>

#include "common/input_error.h"
#include "common/strict_yaml.h"
#include "runtime/endpoint.h"
#include "runtime/process.h"
#include "runtime/security.h"
#include "sensorsPubSubTypes.h"

namespace stickrep::runtime::bench {

namespace dds = eprosima::fastdds::dds;
using eprosima::fastrtps::types::ReturnCode_t;

const char* ToString(Impl impl) { return impl == Impl::kRuntime ? "runtime" : "raw"; }

namespace {

ParticipantConfig MakeConfig(const LinkConfig& c) {
  ParticipantConfig config;
  config.profile_xml = c.profile_xml;
  config.domain_id = c.domain_id;
  config.name = c.name;
  if (!c.security_dir.empty()) config.security = SecurityConfig{c.security_dir, "bench"};
  return config;
}

// Runtime side: Participant, Writer and Reader from the runtime layer; an executor thread
// drains the Reader (its DDS listener only wakes the executor) and runs the callback.
class RuntimeLink : public PingPongLink {
 public:
  RuntimeLink(const LinkConfig& c, OnSample on_sample)
      : participant_(MakeConfig(c), c.catalog),
        writer_(participant_, c.out_topic),
        reader_(participant_, executor_, c.in_topic, std::move(on_sample)),
        spinner_([this] { executor_.Spin(running_, Executor::Clock::time_point::max()); }) {}
  ~RuntimeLink() override {
    running_ = false;
    executor_.Notify();
    spinner_.join();
  }

  bool Send(msgs::Image& sample) override { return writer_.Publish(sample, WallClockNowNs()); }
  bool Matched() const override {
    return writer_.counters().matched.load() > 0 && reader_.counters().matched.load() > 0;
  }

 private:
  Participant participant_;
  Executor executor_;
  Writer<msgs::ImagePubSubType> writer_;
  Reader<msgs::ImagePubSubType> reader_;
  std::atomic<bool> running_{true};
  std::thread spinner_;
};

// Raw side: the plain Fast DDS API. The participant gets the factory's default participant
// QoS as the runtime's does, the endpoints get the same QoS through
// ToDataWriterQos/ToDataReaderQos, and the listener takes samples on the DDS thread.
class RawLink : public PingPongLink,
                public dds::DataReaderListener,
                public dds::DataWriterListener {
 public:
  RawLink(const LinkConfig& c, OnSample on_sample) : on_sample_(std::move(on_sample)) {
    try {
      CreateParticipant(c);
      CreateEndpoints(c);
    } catch (...) {
      DeleteParticipant();
      throw;
    }
  }
  ~RawLink() override { DeleteParticipant(); }

  bool Send(msgs::Image& sample) override { return writer_->write(&sample); }
  bool Matched() const override { return writers_matched_ > 0 && readers_matched_ > 0; }

  void on_data_available(dds::DataReader* reader) override {
    dds::SampleInfo info;
    while (reader->take_next_sample(&sample_, &info) == ReturnCode_t::RETCODE_OK) {
      if (info.valid_data) on_sample_(sample_);
    }
  }
  void on_subscription_matched(dds::DataReader*,
                               const dds::SubscriptionMatchedStatus& s) override {
    writers_matched_ = s.current_count;
  }
  void on_publication_matched(dds::DataWriter*,
                              const dds::PublicationMatchedStatus& s) override {
    readers_matched_ = s.current_count;
  }

 private:
  void CreateParticipant(const LinkConfig& c);
  void CreateEndpoints(const LinkConfig& c);
  void DeleteParticipant();

  OnSample on_sample_;
  msgs::Image sample_;  // reused by every take
  std::atomic<int> writers_matched_{0};
  std::atomic<int> readers_matched_{0};
  dds::DomainParticipant* participant_ = nullptr;
  dds::DataWriter* writer_ = nullptr;
};

void RawLink::CreateParticipant(const LinkConfig& c) {
  auto* factory = dds::DomainParticipantFactory::get_instance();
  dds::DomainParticipantQos pqos = factory->get_default_participant_qos();
  pqos.name(c.name);
  if (!c.security_dir.empty()) ApplySecurity(SecurityConfig{c.security_dir, "bench"}, pqos);
  participant_ = factory->create_participant(c.domain_id, pqos);
  if (participant_ == nullptr) {
    throw std::runtime_error("could not create a DDS participant on domain " +
                             std::to_string(c.domain_id));
  }
  dds::TypeSupport type(new msgs::ImagePubSubType());
  if (type.register_type(participant_) != ReturnCode_t::RETCODE_OK) {
    throw std::runtime_error("could not register the Image type");
  }
}

void RawLink::DeleteParticipant() {
  if (participant_ == nullptr) return;
  participant_->delete_contained_entities();
  dds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
  participant_ = nullptr;
}

void RawLink::CreateEndpoints(const LinkConfig& c) {
  const std::string type_name = msgs::ImagePubSubType().getName();
  dds::Topic* out = participant_->create_topic(c.out_topic, type_name, dds::TOPIC_QOS_DEFAULT);
  dds::Topic* in = participant_->create_topic(c.in_topic, type_name, dds::TOPIC_QOS_DEFAULT);
  dds::Publisher* pub = participant_->create_publisher(dds::PUBLISHER_QOS_DEFAULT);
  dds::Subscriber* sub = participant_->create_subscriber(dds::SUBSCRIBER_QOS_DEFAULT);
  if (out == nullptr || in == nullptr || pub == nullptr || sub == nullptr) {
    throw std::runtime_error("could not create the raw DDS topics, publisher or subscriber");
  }
  writer_ = pub->create_datawriter(
      out, ToDataWriterQos(c.catalog.ForTopic(c.out_topic), pub->get_default_datawriter_qos()),
      this);
  dds::DataReader* reader = sub->create_datareader(
      in, ToDataReaderQos(c.catalog.ForTopic(c.in_topic), sub->get_default_datareader_qos()),
      this);
  if (writer_ == nullptr || reader == nullptr) {
    throw std::runtime_error("could not create the raw DDS writer or reader");
  }
}

}  // namespace

void UseDefaultParticipantProfile(const std::string& xml_file) {
  auto* factory = dds::DomainParticipantFactory::get_instance();
  // Fast DDS 2.9 reads the default participant profile only when it first loads profiles;
  // a file loaded later changes the default only once the default is reset.
  factory->load_profiles();
  if (factory->load_XML_profiles_file(xml_file) != ReturnCode_t::RETCODE_OK) {
    throw InputError(xml_file, 0, "", "Fast DDS could not load this XML profile file");
  }
  factory->set_default_participant_qos(dds::PARTICIPANT_QOS_DEFAULT);
  if (factory->get_default_participant_qos() == dds::PARTICIPANT_QOS_DEFAULT) {
    throw InputError(xml_file, 0, "",
                     "no participant profile with is_default_profile=\"true\" in this file");
  }
}

std::unique_ptr<PingPongLink> MakeLink(Impl impl, const LinkConfig& config,
                                       PingPongLink::OnSample on_sample) {
  if (impl == Impl::kRuntime) return std::make_unique<RuntimeLink>(config, std::move(on_sample));
  return std::make_unique<RawLink>(config, std::move(on_sample));
}

QosCatalog BenchCatalog(const QosProfile& p, const std::string& source_file) {
  // The catalog is only loadable from YAML, so the profile is written back as YAML under
  // its own name with the two bench streams pointing at it.
  std::string text = fmt::format(
      "qos:\n  profiles:\n    {}:\n      reliability: {}\n      durability: {}\n"
      "      history_depth: {}\n      deadline_s: {}\n      liveliness_lease_s: {}\n"
      "      publish_mode: {}\n  streams:\n",
      p.name, ToString(p.reliability), ToString(p.durability), p.history_depth, p.deadline_s,
      p.liveliness_lease_s, ToString(p.publish_mode));
  for (const char* topic : {kPingTopic, kPongTopic}) {
    text += fmt::format(
        "    - topic: {}\n      profile: {}\n      reason: transport benchmark with the {} "
        "profile of {}\n",
        topic, p.name, p.name, source_file);
  }
  return QosCatalog::Load(StrictYaml::LoadString(text, source_file + " (bench copy)"));
}

}  // namespace stickrep::runtime::bench
