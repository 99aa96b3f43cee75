#include "recording/replayer.h"

#include <fmt/format.h>
#include <fmt/ostream.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ostream>
#include <set>

#include "common/input_error.h"
#include "common/quantile.h"
#include "console/message_types.h"

namespace stickrep::recording {

namespace {

using runtime::QosProfile;
using Clock = std::chrono::steady_clock;

// The QoS the (first) writer of a topic offered when it was recorded; keep-last 1 best
// effort where nothing was recorded.
QosProfile RecordedQos(const bag::TopicInfo& t, const std::string& file) {
  QosProfile q;
  q.name = "replay";
  q.reliability = QosProfile::Reliability::kBestEffort;
  nlohmann::json offered;
  try {
    offered = nlohmann::json::parse(t.offered_qos_profiles.empty() ? "[]" : t.offered_qos_profiles);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, 0, "topics." + t.name + ".offered_qos_profiles",
                     std::string("not JSON: ") + e.what());
  }
  if (!offered.is_array() || offered.empty()) return q;
  const nlohmann::json& w = offered.front();
  const std::string profile = w.value("profile", "");
  if (!profile.empty()) q.name = profile;
  q.reliability = w.value("reliability", "") == "reliable" ? QosProfile::Reliability::kReliable
                                                           : QosProfile::Reliability::kBestEffort;
  q.durability = w.value("durability", "") == "transient_local"
                     ? QosProfile::Durability::kTransientLocal
                     : QosProfile::Durability::kVolatile;
  q.deadline_s = w.value("deadline_s", 0.0);
  q.liveliness_lease_s = w.value("liveliness_lease_s", 0.0);
  const std::string history = w.value("history", "");
  if (history == "keep_all") {
    q.history_depth = 0;
  } else if (history.rfind("keep_last ", 0) == 0) {
    q.history_depth = std::max(1, std::atoi(history.c_str() + 10));
  }
  q.publish_mode = w.value("publish_mode", "") == "asynchronous"
                       ? QosProfile::PublishMode::kAsynchronous
                       : QosProfile::PublishMode::kSynchronous;
  return q;
}

}  // namespace

void ValidateReplayOptions(const ReplayOptions& o) {
  if (!(o.rate >= 0.5 && o.rate <= 20.0)) {
    throw InputError("--rate", 0, std::to_string(o.rate), "the rate must be within 0.5 to 20");
  }
  if (!(o.start_s >= 0.0)) throw InputError("--start", 0, "", "must be >= 0 s");
  if (!(o.duration_s >= 0.0)) throw InputError("--duration", 0, "", "must be >= 0 s (0: to the end)");
}

Replayer::Replayer(runtime::Participant& participant, const ReplayOptions& options)
    : options_(options), reader_(options.file) {
  ValidateReplayOptions(options_);
  const std::set<std::string> wanted(options_.topics.begin(), options_.topics.end());
  std::set<std::string> asked = wanted;
  for (const auto& [from, to] : options_.remap) {
    const bool recorded = std::any_of(reader_.topics().begin(), reader_.topics().end(),
                                      [&](const bag::TopicInfo& t) { return t.name == from; });
    if (!recorded) {
      throw InputError("--remap", 0, from + ":" + to, "'" + from + "' is not in " + options_.file);
    }
  }
  for (const bag::TopicInfo& t : reader_.topics()) {
    if (!wanted.empty() && wanted.count(t.name) == 0) continue;
    asked.erase(t.name);
    const console::MessageType* type = console::FindMessageType(t.type);
    if (type == nullptr) {
      throw InputError(options_.file, 0, "topics." + t.name,
                       "type '" + t.type + "' is not one this build knows; it cannot be replayed");
    }
    const auto remapped = options_.remap.find(t.name);
    const std::string topic = remapped == options_.remap.end() ? t.name : remapped->second;
    writers_[t.id] = std::make_unique<runtime::RawWriter>(participant, topic, type->make_support,
                                                          RecordedQos(t, options_.file));
    topic_names_[t.id] = topic;
  }
  if (!asked.empty()) {
    throw InputError("--topics", 0, *asked.begin(),
                     "not a topic of " + options_.file + " (stickrep-bag info lists them)");
  }
  const auto [first, last] = reader_.TimeRange();
  begin_ns_ = first + static_cast<std::int64_t>(options_.start_s * 1e9);
  end_ns_ = options_.duration_s > 0.0
                ? std::min(last, begin_ns_ + static_cast<std::int64_t>(options_.duration_s * 1e9))
                : last;
  if (begin_ns_ > last) {
    throw InputError("--start", 0, std::to_string(options_.start_s),
                     fmt::format("the recording is only {:.1f} s long", (last - first) * 1e-9));
  }
}

Replayer::~Replayer() { Stop(); }

void Replayer::Start(SentCallback on_sent) {
  thread_ = std::thread([this, on_sent] { Run(on_sent); });
}

void Replayer::Stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

void Replayer::Run(SentCallback on_sent) {
  // Readers first (bounded), so that the first samples are not sent into the void.
  const auto wait_until =
      Clock::now() + std::chrono::milliseconds(static_cast<int>(options_.wait_for_readers_s * 1e3));
  auto all_matched = [&] {
    return std::all_of(writers_.begin(), writers_.end(),
                       [](const auto& w) { return w.second->matched() > 0; });
  };
  while (!stop_ && !all_matched() && Clock::now() < wait_until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  for (const auto& [id, w] : writers_) {
    if (w->matched() == 0) report_.without_readers.push_back(w->topic());
  }
  std::vector<double> errors_ms;
  const auto start = Clock::now();
  do {
    report_.passes++;
    if (!OnePass(on_sent, errors_ms)) break;
  } while (options_.loop && !stop_);
  report_.finished = !stop_;
  report_.duration_s = std::chrono::duration<double>(Clock::now() - start).count();
  report_.error_p50_ms = Quantile(errors_ms, 0.50);
  report_.error_p99_ms = Quantile(errors_ms, 0.99);
  report_.error_max_ms =
      errors_ms.empty() ? 0.0 : *std::max_element(errors_ms.begin(), errors_ms.end());
  done_ = true;
}

bool Replayer::OnePass(const SentCallback& on_sent, std::vector<double>& errors_ms) {
  const auto pass_start = Clock::now();
  bool completed = true;
  reader_.ForEach(
      [&](const bag::Message& m) {
        const auto w = writers_.find(m.topic_id);
        if (w == writers_.end()) return true;
        const auto due = pass_start + std::chrono::nanoseconds(static_cast<std::int64_t>(
                                          (m.timestamp_ns - begin_ns_) / options_.rate));
        // Sleep in slices, so that a stop is heard within 50 ms.
        while (!stop_ && Clock::now() + std::chrono::milliseconds(50) < due) {
          std::this_thread::sleep_for(std::chrono::milliseconds(50));
        }
        if (stop_) {
          completed = false;
          return false;
        }
        std::this_thread::sleep_until(due);
        errors_ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - due).count());
        if (w->second->Publish(m.data.data(), m.data.size())) {
          report_.sent[w->second->topic()]++;
        } else {
          report_.refused++;
        }
        if (on_sent) on_sent(w->second->topic(), m);
        return true;
      },
      begin_ns_, end_ns_);
  return completed;
}

std::string ReplayReportLine(const ReplayReport& r, double rate) {
  std::uint64_t total = 0;
  std::string per_topic;
  for (const auto& [topic, n] : r.sent) {
    per_topic += fmt::format("{}{} {}", per_topic.empty() ? "" : ", ", topic, n);
    total += n;
  }
  std::string line = fmt::format(
      "replayed {} samples ({}) in {:.1f} s at rate {:g} ({} pass{}{}); {} refused by DDS; send "
      "time - scheduled time: p50 {:.3f} ms, p99 {:.3f} ms, max {:.3f} ms",
      total, per_topic, r.duration_s, rate, r.passes, r.passes == 1 ? "" : "es",
      r.finished ? "" : ", stopped before the end", r.refused, r.error_p50_ms, r.error_p99_ms,
      r.error_max_ms);
  if (!r.without_readers.empty()) {
    std::string list;
    for (const auto& t : r.without_readers) list += (list.empty() ? "" : ", ") + t;
    line += "; no reader at the start on " + list;
  }
  return line;
}

}  // namespace stickrep::recording
