#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "bag/bag_storage.h"
#include "runtime/participant.h"
#include "runtime/raw_endpoint.h"

namespace stickrep::recording {

struct ReplayOptions {
  std::string file;
  double rate = 1.0;                // recorded seconds per wall second, 0.5 to 20
  double start_s = 0.0;             // skip this much of the recording
  double duration_s = 0.0;          // replay this much of it; 0: to the end
  bool loop = false;                // start again at the end, until stopped
  std::vector<std::string> topics;  // empty: every recorded topic
  std::map<std::string, std::string> remap;  // recorded topic -> topic to publish on
  double wait_for_readers_s = 5.0;  // before the first sample: until every topic has a reader
};

// Checks the ranges and the remap/topic names; throws InputError naming the option.
void ValidateReplayOptions(const ReplayOptions& options);

struct ReplayReport {
  std::map<std::string, std::uint64_t> sent;  // by published topic
  std::uint64_t refused = 0;                  // writes DDS refused
  int passes = 0;                             // times through the recording
  double duration_s = 0.0;                    // wall time from the first sample to the last
  // Send time minus scheduled time, ms, over every sample.
  double error_p50_ms = 0.0, error_p99_ms = 0.0, error_max_ms = 0.0;
  std::vector<std::string> without_readers;   // topics no reader had matched at the start
  bool finished = false;                      // reached the end (not stopped)
};

// Publishes a recording's samples unchanged (payload bytes as recorded, so the samples'
// header stamps are the recorded ones; the DDS source timestamp is the send time), each
// topic with the QoS its writer offered when it was recorded, at the recorded pace scaled
// by the rate. One implementation for stickrep-replay and the virtual robot's replay
// source. Runs on a thread of its own; the caller keeps spinning its executor.
class Replayer {
 public:
  using SentCallback = std::function<void(const std::string& topic, const bag::Message& m)>;

  // Opens the file and creates a writer per replayed topic. Throws InputError for a file
  // that is not a recording, a type this build does not know, or bad options.
  Replayer(runtime::Participant& participant, const ReplayOptions& options);
  ~Replayer();
  Replayer(const Replayer&) = delete;
  Replayer& operator=(const Replayer&) = delete;

  // Starts replaying; `on_sent` (optional) runs on the replay thread after each sample.
  void Start(SentCallback on_sent = {});
  // Asks the thread to stop and waits for it.
  void Stop();
  bool done() const { return done_.load(); }
  // Valid once done() (or after Stop()).
  const ReplayReport& report() const { return report_; }
  // Seconds of recording that will be replayed in one pass.
  double span_s() const { return (end_ns_ - begin_ns_) * 1e-9; }
  // The published topic of each replayed recorded topic id.
  const std::map<std::int64_t, std::string>& topics() const { return topic_names_; }

 private:
  void Run(SentCallback on_sent);
  bool OnePass(const SentCallback& on_sent, std::vector<double>& errors_ms);

  ReplayOptions options_;
  bag::BagReader reader_;
  std::int64_t begin_ns_ = 0, end_ns_ = 0;
  std::map<std::int64_t, std::unique_ptr<runtime::RawWriter>> writers_;  // by topic id
  std::map<std::int64_t, std::string> topic_names_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> done_{false};
  std::thread thread_;
  ReplayReport report_;
};

// The report in one line, as the tools print it.
std::string ReplayReportLine(const ReplayReport& report, double rate);

}  // namespace stickrep::recording
