#include "recording/recorder.h"

#include <fmt/format.h>
#include <fmt/ostream.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <memory>
#include <set>
#include <ostream>
#include <sstream>

#include "bag/bag_storage.h"
#include "common/input_error.h"
#include "console/console.h"
#include "console/message_types.h"
#include "idl_text.h"
#include "runtime/process.h"
#include "runtime/raw_endpoint.h"

namespace stickrep::recording {

namespace {

using runtime::QosProfile;

// Samples a recorder's reader keeps until they are taken: 10 s of camera frames at 10x.
constexpr int kRecorderDepth = 500;

std::string ReadWholeFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The writers' QoS of one topic as discovery shows it, stored as the topic's
// offered_qos_profiles (one JSON object per writer).
nlohmann::json OfferedQos(const std::vector<runtime::DiscoveredEndpoint>& writers) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& w : writers) {
    list.push_back({{"reliability", w.reliability},
                    {"durability", w.durability},
                    {"deadline_s", w.deadline_s},
                    {"liveliness_lease_s", w.liveliness_lease_s},
                    {"profile", runtime::UserDataField(w.user_data, "profile")},
                    {"history", runtime::UserDataField(w.user_data, "history")},
                    {"publish_mode", runtime::UserDataField(w.user_data, "publish_mode")}});
  }
  return list;
}

// A reader that matches every writer of the topic and keeps what they keep: reliable when
// all offer it, transient-local when all do (so a latched map is recorded too), a deep
// history so that the file's commits do not overwrite samples not yet taken.
QosProfile RecorderQos(const std::vector<runtime::DiscoveredEndpoint>& writers) {
  QosProfile q;
  q.name = "recorder";
  const bool all_reliable = std::all_of(writers.begin(), writers.end(),
                                        [](const auto& w) { return w.reliability == "reliable"; });
  const bool all_latched = std::all_of(writers.begin(), writers.end(), [](const auto& w) {
    return w.durability == "transient_local";
  });
  q.reliability = all_reliable ? QosProfile::Reliability::kReliable
                               : QosProfile::Reliability::kBestEffort;
  q.durability = all_latched ? QosProfile::Durability::kTransientLocal
                             : QosProfile::Durability::kVolatile;
  q.history_depth = kRecorderDepth;
  return q;
}

// One recorded topic: its row (made with its first sample, so the file lists what was
// recorded) and its tally.
struct Subscription {
  bag::TopicInfo info;
  std::int64_t id = -1;
  TopicTally* tally = nullptr;
};

class Session {
 public:
  Session(const RecordOptions& o, std::ostream& log)
      : options_(o),
        log_(log),
        // Announced every 0.2 s, so that a robot started after the recorder finds it at once.
        domain_(console::JoinDomain(o.system_file, o.domain_id, o.deployment, "stickrep-record",
                                    1.0, 0.2)),
        // The session commits (every batch_s at most), so that it knows what is stored.
        bag_(o.output, 1e9) {
    bag_.SetSizeLimit(o.max_bytes);
    start_ns_ = runtime::WallClockNowNs();
    WriteStartMetadata();
    SubscribeCatalogued();
  }

  RecordReport Run() {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    auto next_discovery = start;
    while (runtime::KeepRunning().load() && failure_.empty()) {
      const auto now = Clock::now();
      if (options_.duration_s > 0.0 &&
          std::chrono::duration<double>(now - start).count() >= options_.duration_s) {
        break;
      }
      if (now >= next_discovery) {
        Subscribe();
        next_discovery = now + std::chrono::milliseconds(
                                   static_cast<int>(options_.discovery_period_s * 1000));
      }
      executor_.SpinOnce(std::chrono::milliseconds(20));
      // A quiet stream still reaches the file within a batch's time.
      if (pending_ && std::chrono::duration<double>(Clock::now() - last_commit_).count() >=
                          options_.batch_s) {
        Commit();
      }
    }
    if (failure_.empty()) executor_.SpinOnce(std::chrono::milliseconds(0));  // what is waiting
    Commit();
    for (const auto& r : readers_) report_.topics[r->topic()].lost = r->lost();
    StoreDiscoveredQos();
    report_.duration_s = (runtime::WallClockNowNs() - start_ns_) * 1e-9;
    report_.failure = failure_;
    WriteEndMetadata();
    readers_.clear();
    return report_;
  }

 private:
  bool Wanted(const std::string& topic) const {
    return options_.topics.empty() ||
           std::find(options_.topics.begin(), options_.topics.end(), topic) !=
               options_.topics.end();
  }

  // StickRep's own topics (the QoS catalogue) are subscribed at once with the QoS their
  // writers are made with, so that a recording started before the robot misses nothing
  // while discovery runs. Their writers' QoS as discovery shows it is stored at the end.
  void SubscribeCatalogued() {
    for (const auto& [topic, stream] : domain_.participant->catalog().streams()) {
      const console::MessageType* type = console::TypeOfTopic(topic);
      if (!Wanted(topic) || type == nullptr) continue;
      const QosProfile& offered = domain_.participant->catalog().ForTopic(topic);
      QosProfile q = offered;
      q.name = "recorder";
      q.history_depth = kRecorderDepth;
      q.deadline_s = 0.0;
      q.liveliness_lease_s = 0.0;
      runtime::DiscoveredEndpoint as_catalogued;
      as_catalogued.reliability = runtime::ToString(offered.reliability);
      as_catalogued.durability = runtime::ToString(offered.durability);
      as_catalogued.deadline_s = offered.deadline_s;
      as_catalogued.liveliness_lease_s = offered.liveliness_lease_s;
      as_catalogued.user_data = runtime::EncodeProfileUserData(offered);
      AddTopic(topic, *type, {as_catalogued}, q);
    }
  }

  // Every other topic with a writer of a known type, as its writers appear.
  void Subscribe() {
    std::map<std::string, std::vector<runtime::DiscoveredEndpoint>> writers;
    for (const auto& e : domain_.listener->Endpoints()) {
      if (e.is_writer && Wanted(e.topic) && subscriptions_.count(e.topic) == 0) {
        writers[e.topic].push_back(e);
      }
    }
    for (const auto& [topic, ws] : writers) {
      const std::string& type_name = ws.front().type;
      const console::MessageType* type = console::FindMessageType(type_name);
      if (type == nullptr) {
        if (unknown_.insert(topic).second) {
          fmt::print(log_, "stickrep-record: {} carries {}, a type this build does not know: "
                     "not recorded\n", topic, type_name);
        }
        continue;
      }
      AddTopic(topic, *type, ws, RecorderQos(ws));
    }
  }

  void AddTopic(const std::string& topic, const console::MessageType& type,
                const std::vector<runtime::DiscoveredEndpoint>& writers, const QosProfile& qos) {
    Subscription& sub = subscriptions_[topic];
    sub.info.name = topic;
    sub.info.type = type.name;
    sub.info.offered_qos_profiles = OfferedQos(writers).dump();
    sub.tally = &report_.topics[topic];
    sub.tally->type = type.name;
    readers_.push_back(std::make_unique<runtime::RawReader>(
        *domain_.participant, executor_, topic, type.make_support, qos,
        [this, &sub](const runtime::RawSample& m, const runtime::RawSampleInfo& i) {
          Store(sub, m, i);
        }));
    fmt::print(log_, "stickrep-record: subscribed to {} ({})\n", topic, type.name);
  }

  void Store(Subscription& sub, const runtime::RawSample& m, const runtime::RawSampleInfo& i) {
    TopicTally& tally = *sub.tally;
    tally.received++;
    if (!failure_.empty()) return;
    try {
      if (sub.id < 0) sub.id = bag_.AddTopic(sub.info);
      bag_.Write(sub.id, i.source_ns, i.reception_ns, m.data.data(), m.data.size());
      batch_.push_back({&tally, m.data.size()});
      pending_ = true;
    } catch (const InputError& e) {
      failure_ = e.what();
      batch_.clear();
      return;
    }
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - last_commit_).count() >=
        options_.batch_s) {
      Commit();
    }
  }

  void Commit() {
    if (!failure_.empty()) return;
    try {
      bag_.Flush();
      for (const auto& [tally, bytes] : batch_) {
        tally->stored++;
        report_.bytes += bytes;
      }
      batch_.clear();
      pending_ = false;
      last_commit_ = std::chrono::steady_clock::now();
    } catch (const InputError& e) {
      failure_ = e.what();
      batch_.clear();
    }
  }

  // The QoS each recorded topic's writers offered, as discovery saw them (catalogued topics
  // were subscribed before their writers were seen).
  void StoreDiscoveredQos() {
    std::map<std::string, std::vector<runtime::DiscoveredEndpoint>> writers;
    for (const auto& e : domain_.listener->Endpoints()) {
      const auto sub = subscriptions_.find(e.topic);
      if (e.is_writer && sub != subscriptions_.end() && sub->second.id >= 0) {
        writers[e.topic].push_back(e);
      }
    }
    try {
      for (const auto& [topic, ws] : writers) {
        bag_.SetTopicQos(subscriptions_[topic].id, OfferedQos(ws).dump());
      }
      bag_.Flush();
    } catch (const InputError& e) {
      // A full file: the catalogue's QoS stays recorded.
      fmt::print(log_, "stickrep-record: the writers' QoS was not stored: {}\n", e.what());
    }
  }

  void WriteStartMetadata() {
    const auto& system = domain_.system;
    bag_.SetMetadata("stickrep_version", STICKREP_VERSION);
    char host[256] = {0};
    gethostname(host, sizeof(host) - 1);
    bag_.SetMetadata("host", runtime::HostLabel(options_.deployment).empty()
                                 ? host
                                 : runtime::HostLabel(options_.deployment));
    bag_.SetMetadata("start_ns", std::to_string(start_ns_));
    bag_.SetMetadata("domain_id", std::to_string(system.domain_id));
    // The settings in force: the system file and what it names.
    for (const auto& [key, path] : {std::pair{"system_file", system.file},
                                    {"qos_file", system.qos_file},
                                    {"robot_file", system.robot_file},
                                    {"map_file", system.map_file}}) {
      bag_.SetMetadata(std::string(key), path);
      bag_.SetMetadata(std::string(key) + ".text", ReadWholeFile(path));
    }
    for (const auto& [file, text] : msgs::IdlFiles()) bag_.SetMetadata("idl/" + file, text);
    bag_.Flush();
  }

  void WriteEndMetadata() {
    nlohmann::json counts = nlohmann::json::object();
    for (const auto& [topic, t] : report_.topics) {
      counts[topic] = {{"type", t.type}, {"received", t.received}, {"stored", t.stored},
                       {"lost", t.lost}};
    }
    try {
      bag_.SetMetadata("end_ns", std::to_string(runtime::WallClockNowNs()));
      bag_.SetMetadata("counts", counts.dump());
      if (!failure_.empty()) bag_.SetMetadata("ended_by", failure_);
      bag_.Flush();
    } catch (const InputError& e) {
      // A full file takes no metadata either; the samples committed are there.
      fmt::print(log_, "stickrep-record: the closing metadata was not written: {}\n", e.what());
    }
  }

  const RecordOptions& options_;
  std::ostream& log_;
  console::DomainSession domain_;
  bag::BagWriter bag_;
  runtime::Executor executor_;
  std::vector<std::unique_ptr<runtime::RawReader>> readers_;
  std::map<std::string, Subscription> subscriptions_;
  std::set<std::string> unknown_;
  std::vector<std::pair<TopicTally*, std::size_t>> batch_;
  bool pending_ = false;
  std::chrono::steady_clock::time_point last_commit_ = std::chrono::steady_clock::now();
  std::int64_t start_ns_ = 0;
  std::string failure_;
  RecordReport report_;
};

}  // namespace

RecordReport Record(const RecordOptions& options, std::ostream& log) {
  Session session(options, log);
  return session.Run();
}

}  // namespace stickrep::recording

namespace stickrep::recording {

void PrintRecordReport(const RecordReport& report, std::ostream& out) {
  fmt::print(out, "{:<28} {:<36} {:>9} {:>9} {:>6}\n", "TOPIC", "TYPE", "RECEIVED", "STORED",
             "LOST");
  std::uint64_t received = 0, stored = 0, lost = 0;
  int silent = 0;
  for (const auto& [topic, t] : report.topics) {
    if (t.received == 0) {
      silent++;
      continue;
    }
    fmt::print(out, "{:<28} {:<36} {:>9} {:>9} {:>6}\n", topic, t.type, t.received, t.stored,
               t.lost);
    received += t.received;
    stored += t.stored;
    lost += t.lost;
  }
  fmt::print(out, "{} topics ({} more subscribed, nothing received), {} samples received, {} "
             "stored, {} lost on the way; {:.1f} MB in {:.1f} s ({:.2f} MB/s)\n",
             report.topics.size() - silent, silent, received, stored, lost,
             report.bytes / 1e6, report.duration_s,
             report.duration_s > 0 ? report.bytes / 1e6 / report.duration_s : 0.0);
  if (!report.failure.empty()) {
    fmt::print(out, "recording ended early: {}; the {} samples committed before are kept\n",
               report.failure, stored);
  }
}

}  // namespace stickrep::recording
