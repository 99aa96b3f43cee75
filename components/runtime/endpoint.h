#pragma once

#include <fastdds/dds/publisher/DataWriterListener.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <thread>

#include "runtime/executor.h"
#include "runtime/guarded_type.h"
#include "runtime/participant.h"

namespace stickrep::runtime {

// Counters of one endpoint, read by the status reporter and by tests.
struct EndpointCounters {
  std::atomic<uint64_t> samples{0};
  std::atomic<int> matched{0};
  std::atomic<uint64_t> deadline_missed{0};
  std::atomic<int> alive_writers{0};
  std::atomic<uint64_t> liveliness_lost_events{0};
};

// Polls `done` until it holds or `timeout_s` passes; true if it held. For set-up and tests
// that must wait for discovery or data without a fixed sleep as the pass condition.
bool WaitFor(const std::function<bool()>& done, double timeout_s);

// Counts a writer's matched readers and missed deadlines (typed and raw writers alike).
class WriterCountingListener : public eprosima::fastdds::dds::DataWriterListener {
 public:
  explicit WriterCountingListener(EndpointCounters& c) : c_(c) {}
  void on_publication_matched(eprosima::fastdds::dds::DataWriter*,
                              const eprosima::fastdds::dds::PublicationMatchedStatus& s) override {
    c_.matched = s.current_count;
  }
  void on_offered_deadline_missed(eprosima::fastdds::dds::DataWriter*,
                                  const eprosima::fastdds::dds::OfferedDeadlineMissedStatus&) override {
    c_.deadline_missed++;
  }

 private:
  EndpointCounters& c_;
};

// A typed writer on one topic with the topic's catalogued QoS. `PubSubType` is the
// fastddsgen support class; every StickRep sample has a `header` that Publish() stamps.
// The part every reader's listener shares: wakes the executor when data arrives and keeps
// the count of matched writers. Each reader adds what it does on a missed deadline or a
// change of liveliness.
class ReaderListener : public eprosima::fastdds::dds::DataReaderListener {
 public:
  ReaderListener(Executor& executor, EndpointCounters& counters)
      : executor_(executor), counters_(counters) {}
  void on_data_available(eprosima::fastdds::dds::DataReader*) override { executor_.Notify(); }
  void on_subscription_matched(eprosima::fastdds::dds::DataReader*,
                               const eprosima::fastdds::dds::SubscriptionMatchedStatus& s) override {
    counters_.matched = s.current_count;
  }

 private:
  Executor& executor_;
  EndpointCounters& counters_;
};

template <typename PubSubType>
class Writer {
 public:
  using Sample = typename PubSubType::type;

  Writer(Participant& participant, const std::string& topic)
      : participant_(participant), topic_(topic), listener_(counters_) {
    writer_ =
        participant_.CreateDataWriter(topic, new GuardedPubSubType<PubSubType>(), &listener_);
  }
  ~Writer() { participant_.DeleteDataWriter(writer_); }
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  // Stamps the header (time, next sequence number) and writes; false if DDS refused.
  bool Publish(Sample& sample, int64_t stamp_ns) {
    sample.header().stamp_ns(stamp_ns);
    sample.header().sequence_number(++sequence_);
    const bool ok = writer_->write(&sample);
    if (ok) counters_.samples++;
    return ok;
  }
  const std::string& topic() const { return topic_; }
  const EndpointCounters& counters() const { return counters_; }
  bool WaitForMatched(int readers, double timeout_s) const {
    return WaitFor([&] { return counters_.matched.load() >= readers; }, timeout_s);
  }

 private:
  Participant& participant_;
  std::string topic_;
  EndpointCounters counters_;
  WriterCountingListener listener_;
  eprosima::fastdds::dds::DataWriter* writer_ = nullptr;
  uint32_t sequence_ = 0;
};

// A typed reader on one topic. DDS threads only count and wake the executor; samples and
// events reach the callbacks on the executor's thread, and only while the process is active
// (the executor is not spun before activation).
template <typename PubSubType>
class Reader : public Drainable {
 public:
  using Sample = typename PubSubType::type;
  using SampleCallback = std::function<void(const Sample&)>;

  Reader(Participant& participant, Executor& executor, const std::string& topic,
         SampleCallback on_sample)
      : participant_(participant),
        executor_(executor),
        topic_(topic),
        on_sample_(std::move(on_sample)),
        listener_(*this) {
    reader_ =
        participant_.CreateDataReader(topic, new GuardedPubSubType<PubSubType>(), &listener_);
    executor_.Add(this);
  }
  ~Reader() override {
    executor_.Remove(this);
    participant_.DeleteDataReader(reader_);
  }
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;

  // Called on the executor thread when the requested deadline passed with no sample.
  void OnDeadlineMissed(std::function<void()> fn) { on_deadline_ = std::move(fn); }
  // Called on the executor thread when the number of live writers changes.
  void OnLivelinessChanged(std::function<void(int alive_writers)> fn) {
    on_liveliness_ = std::move(fn);
  }
  // Called on the executor thread for an instance whose writers are all gone (keyed topics):
  // the argument holds the key fields.
  void OnInstanceGone(std::function<void(const Sample& key_holder)> fn) {
    on_instance_gone_ = std::move(fn);
  }

  void Drain() override {
    if (deadline_pending_.exchange(false) && on_deadline_) on_deadline_();
    if (liveliness_pending_.exchange(false) && on_liveliness_) {
      on_liveliness_(counters_.alive_writers.load());
    }
    Sample sample;
    eprosima::fastdds::dds::SampleInfo info;
    while (reader_->take_next_sample(&sample, &info) ==
           eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
      if (info.valid_data) {
        counters_.samples++;
        source_timestamp_ns_ = info.source_timestamp.to_ns();
        on_sample_(sample);
      } else if (on_instance_gone_ &&
                 info.instance_state != eprosima::fastdds::dds::ALIVE_INSTANCE_STATE) {
        Sample key_holder;
        if (reader_->get_key_value(&key_holder, info.instance_handle) ==
            eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
          on_instance_gone_(key_holder);
        }
      }
    }
  }

  const std::string& topic() const { return topic_; }
  const EndpointCounters& counters() const { return counters_; }
  // Wall-clock time (ns) the writer wrote the sample being delivered: valid inside the
  // sample callback, whatever time the sample's header carries (simulated time).
  int64_t source_timestamp_ns() const { return source_timestamp_ns_; }
  bool WaitForMatched(int writers, double timeout_s) const {
    return WaitFor([&] { return counters_.matched.load() >= writers; }, timeout_s);
  }

 private:
  class Listener : public ReaderListener {
   public:
    explicit Listener(Reader& r) : ReaderListener(r.executor_, r.counters_), r_(r) {}
    void on_requested_deadline_missed(
        eprosima::fastdds::dds::DataReader*,
        const eprosima::fastdds::dds::RequestedDeadlineMissedStatus&) override {
      r_.counters_.deadline_missed++;
      r_.deadline_pending_ = true;
      r_.executor_.Notify();
    }
    void on_liveliness_changed(eprosima::fastdds::dds::DataReader*,
                               const eprosima::fastdds::dds::LivelinessChangedStatus& s) override {
      r_.counters_.alive_writers = s.alive_count;
      if (s.not_alive_count_change > 0) r_.counters_.liveliness_lost_events++;
      r_.liveliness_pending_ = true;
      r_.executor_.Notify();
    }

   private:
    Reader& r_;
  };

  Participant& participant_;
  Executor& executor_;
  std::string topic_;
  SampleCallback on_sample_;
  std::function<void()> on_deadline_;
  std::function<void(int)> on_liveliness_;
  std::function<void(const Sample&)> on_instance_gone_;
  EndpointCounters counters_;
  int64_t source_timestamp_ns_ = 0;
  std::atomic<bool> deadline_pending_{false};
  std::atomic<bool> liveliness_pending_{false};
  Listener listener_;
  eprosima::fastdds::dds::DataReader* reader_ = nullptr;
};

}  // namespace stickrep::runtime
