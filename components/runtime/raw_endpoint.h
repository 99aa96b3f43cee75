#pragma once

// Writers and readers of serialized samples (raw_type.h) on any StickRep topic, with a QoS
// profile given by the caller instead of the catalogue's: the recorder subscribes with the
// QoS each writer offers, the replayer publishes with the QoS that was recorded.

#include <fastdds/dds/publisher/DataWriterListener.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "runtime/endpoint.h"
#include "runtime/executor.h"
#include "runtime/participant.h"
#include "runtime/qos_catalog.h"
#include "runtime/raw_type.h"

namespace stickrep::runtime {

// Makes a new instance of a type's real support class (console/message_types.h has them).
using SupportFactory = std::function<eprosima::fastdds::dds::TopicDataType*()>;

class RawWriter {
 public:
  RawWriter(Participant& participant, const std::string& topic, const SupportFactory& real,
            const QosProfile& qos);
  ~RawWriter();
  RawWriter(const RawWriter&) = delete;
  RawWriter& operator=(const RawWriter&) = delete;

  // Writes the payload unchanged; false if DDS refused it.
  bool Publish(const std::uint8_t* data, std::size_t size);
  const std::string& topic() const { return topic_; }
  int matched() const { return counters_.matched.load(); }
  const EndpointCounters& counters() const { return counters_; }

 private:
  Participant& participant_;
  std::string topic_;
  EndpointCounters counters_;
  WriterCountingListener listener_;
  RawSample sample_;
  eprosima::fastdds::dds::DataWriter* writer_ = nullptr;
};

// What DDS says of one received sample.
struct RawSampleInfo {
  std::int64_t source_ns = 0;     // the writer's source timestamp
  std::int64_t reception_ns = 0;  // when this participant received it
  std::string writer_guid;
  std::uint64_t sequence_number = 0;  // the writer's DDS sequence number
};

// Samples reach the callback on the executor's thread (as with Reader). Gaps in each
// writer's DDS sequence numbers are counted as lost: dropped on the way (best effort) or
// overwritten in this reader's history before they were taken.
class RawReader : public Drainable {
 public:
  using Callback = std::function<void(const RawSample&, const RawSampleInfo&)>;
  RawReader(Participant& participant, Executor& executor, const std::string& topic,
            const SupportFactory& real, const QosProfile& qos, Callback on_sample);
  ~RawReader() override;
  RawReader(const RawReader&) = delete;
  RawReader& operator=(const RawReader&) = delete;

  void Drain() override;
  const std::string& topic() const { return topic_; }
  std::uint64_t received() const { return counters_.samples.load(); }
  std::uint64_t lost() const { return lost_; }
  int matched() const { return counters_.matched.load(); }
  // Deadlines (of the QoS given) that passed with no sample, as DDS reports them.
  std::uint64_t deadlines_missed() const { return counters_.deadline_missed.load(); }
  int alive_writers() const { return counters_.alive_writers.load(); }
  // The GUIDs of writers whose liveliness was lost, once per loss, in order.
  std::vector<std::string> writers_lost() const;

 private:
  class Listener : public ReaderListener {
   public:
    explicit Listener(RawReader& r) : ReaderListener(r.executor_, r.counters_), r_(r) {}
    void on_requested_deadline_missed(
        eprosima::fastdds::dds::DataReader*,
        const eprosima::fastdds::dds::RequestedDeadlineMissedStatus& s) override;
    void on_liveliness_changed(eprosima::fastdds::dds::DataReader*,
                               const eprosima::fastdds::dds::LivelinessChangedStatus& s) override;

   private:
    RawReader& r_;
  };

  Participant& participant_;
  Executor& executor_;
  std::string topic_;
  Callback on_sample_;
  EndpointCounters counters_;
  std::map<std::string, std::uint64_t> last_sequence_;  // per writer GUID
  std::uint64_t lost_ = 0;
  mutable std::mutex mutex_;  // guards writers_lost_ (written on a DDS thread)
  std::vector<std::string> writers_lost_;
  Listener listener_;
  eprosima::fastdds::dds::DataReader* reader_ = nullptr;
};

}  // namespace stickrep::runtime
