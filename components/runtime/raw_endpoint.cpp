#include "runtime/raw_endpoint.h"

#include <fastdds/dds/subscriber/SampleInfo.hpp>

#include <fastdds/rtps/common/InstanceHandle.h>

#include <algorithm>

#include "runtime/discovery.h"

namespace stickrep::runtime {

namespace dds = eprosima::fastdds::dds;

namespace {

dds::TopicDataType* MakeRaw(const SupportFactory& real) {
  return new RawPubSubType(std::unique_ptr<dds::TopicDataType>(real()));
}

}  // namespace

RawWriter::RawWriter(Participant& participant, const std::string& topic,
                     const SupportFactory& real, const QosProfile& qos)
    : participant_(participant), topic_(topic), listener_(counters_) {
  writer_ = participant_.CreateDataWriter(topic, MakeRaw(real), &listener_, qos);
}

RawWriter::~RawWriter() { participant_.DeleteDataWriter(writer_); }

bool RawWriter::Publish(const std::uint8_t* data, std::size_t size) {
  sample_.data.assign(data, data + size);
  const bool ok = writer_->write(&sample_);
  if (ok) counters_.samples++;
  return ok;
}

RawReader::RawReader(Participant& participant, Executor& executor, const std::string& topic,
                     const SupportFactory& real, const QosProfile& qos, Callback on_sample)
    : participant_(participant),
      executor_(executor),
      topic_(topic),
      on_sample_(std::move(on_sample)),
      listener_(*this) {
  reader_ = participant_.CreateDataReader(topic, MakeRaw(real), &listener_, qos);
  executor_.Add(this);
}

RawReader::~RawReader() {
  executor_.Remove(this);
  participant_.DeleteDataReader(reader_);
}

void RawReader::Listener::on_requested_deadline_missed(
    dds::DataReader*, const dds::RequestedDeadlineMissedStatus& s) {
  r_.counters_.deadline_missed += s.total_count_change;
}

void RawReader::Listener::on_liveliness_changed(dds::DataReader*,
                                                const dds::LivelinessChangedStatus& s) {
  r_.counters_.alive_writers = s.alive_count;
  if (s.not_alive_count_change <= 0) return;
  r_.counters_.liveliness_lost_events++;
  eprosima::fastrtps::rtps::GUID_t writer;
  eprosima::fastrtps::rtps::iHandle2GUID(writer, s.last_publication_handle);
  std::lock_guard<std::mutex> lock(r_.mutex_);
  r_.writers_lost_.push_back(GuidText(writer));
}

std::vector<std::string> RawReader::writers_lost() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return writers_lost_;
}

void RawReader::Drain() {
  RawSample sample;
  dds::SampleInfo info;
  while (reader_->take_next_sample(&sample, &info) ==
         eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
    if (!info.valid_data) continue;
    counters_.samples++;
    RawSampleInfo i;
    i.source_ns = info.source_timestamp.to_ns();
    i.reception_ns = info.reception_timestamp.to_ns();
    i.writer_guid = GuidText(info.sample_identity.writer_guid());
    i.sequence_number = info.sample_identity.sequence_number().to64long();
    auto [last, first] = last_sequence_.try_emplace(i.writer_guid, i.sequence_number);
    if (!first) {
      if (i.sequence_number > last->second + 1) lost_ += i.sequence_number - last->second - 1;
      last->second = std::max(last->second, i.sequence_number);
    }
    on_sample_(sample, i);
  }
}

}  // namespace stickrep::runtime
