#include "console/console.h"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <algorithm>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <tuple>
#include <ostream>

#include "common/input_error.h"
#include "console/message_json.h"
#include "console/doctor.h"
#include "console/message_types.h"
#include "console/topic_stats.h"
#include "missionPubSubTypes.h"
#include "systemPubSubTypes.h"
#include "runtime/endpoint.h"
#include "runtime/raw_endpoint.h"
#include "runtime/process.h"
#include "runtime/system_config.h"

namespace stickrep::console {

namespace {

using Session = DomainSession;

Session Join(const ConsoleOptions& o) { return JoinAsConsole(o); }

std::string Seconds(double s) { return s <= 0.0 ? "-" : fmt::format("{:g} s", s); }

// Counts the samples and serialized bytes of one topic (`bw`).
struct Traffic {
  uint64_t samples = 0;
  uint64_t bytes = 0;
};

// A reader of `topic` that keeps samples serialized, with the catalogue's QoS for the topic
// (or best effort, which matches any writer, for a topic the catalogue does not name).
std::unique_ptr<runtime::RawReader> ReadRaw(Session& s, runtime::Executor& ex,
                                            const std::string& topic, const MessageType& type,
                                            runtime::RawReader::Callback fn) {
  runtime::QosProfile qos;
  if (s.participant->catalog().HasTopic(topic)) {
    qos = s.participant->catalog().ForTopic(topic);
  } else {
    qos.name = "console";
    qos.reliability = runtime::QosProfile::Reliability::kBestEffort;
  }
  return std::make_unique<runtime::RawReader>(*s.participant, ex, topic, type.make_support, qos,
                                              std::move(fn));
}

}  // namespace

DomainSession JoinDomain(const std::string& system_file, int domain_id,
                         const runtime::DeploymentOptions& deployment, const std::string& name,
                         double wait_s, double announcement_period_s, bool shared_memory) {
  DomainSession s;
  s.system = runtime::SystemConfig::LoadFile(system_file);
  if (domain_id >= 0) s.system.domain_id = domain_id;
  runtime::ParticipantConfig config = runtime::MakeParticipantConfig(s.system, deployment, name);
  config.announcement_period_s = announcement_period_s;
  config.shared_memory = shared_memory && s.system.shared_memory;
  s.participant = std::make_unique<runtime::Participant>(
      config, runtime::QosCatalog::LoadFile(s.system.qos_file));
  s.listener = &s.participant->discovery();
  if (s.listener->UsesServers()) {
    // Discovery goes through the server: wait (bounded) until it is reached, then listen.
    const bool reached = runtime::WaitFor(
        [&] { return s.listener->ServersReached() > 0 || !runtime::KeepRunning().load(); },
        std::max(5.0, wait_s));
    if (!reached || s.listener->ServersReached() == 0) {
      fmt::print(stderr, "{}: no discovery server reached at {}\n", name,
                 s.participant->servers_text());
    }
  }
  return s;
}

DomainSession JoinAsConsole(const ConsoleOptions& o) {
  return JoinDomain(o.system_file, o.domain_id, o.deployment, "stickrep-console", o.wait_s,
                    /*announcement_period_s=*/0.0, /*shared_memory=*/false);
}

namespace {

// `bw`'s table (or one JSON object): samples, rate, mean size and bytes/s of every topic.
void PrintBandwidth(const std::map<std::string, Traffic>& traffic, double window_s, bool json,
                    std::ostream& out) {
  double total = 0.0;
  nlohmann::json topics = nlohmann::json::array();
  if (!json) {
    fmt::print(out, "{:<26} {:>8} {:>8} {:>12} {:>12}   over {:.3g} s\n", "TOPIC", "SAMPLES", "HZ",
               "MEAN BYTES", "BYTES/S", window_s);
  }
  for (const auto& [topic, t] : traffic) {
    const double rate = t.bytes / window_s;
    const double mean = t.samples ? double(t.bytes) / t.samples : 0.0;
    total += rate;
    topics.push_back({{"topic", topic}, {"samples", t.samples}, {"rate_hz", t.samples / window_s},
                      {"mean_bytes", mean}, {"bytes_per_s", rate}});
    if (!json) {
      fmt::print(out, "{:<26} {:>8} {:>8.1f} {:>12.0f} {:>12.0f}\n", topic, t.samples,
                 t.samples / window_s, mean, rate);
    }
  }
  if (json) {
    out << nlohmann::json{{"window_s", window_s}, {"topics", topics}, {"bytes_per_s", total}}.dump()
        << '\n';
    return;
  }
  fmt::print(out, "{:<26} {:>8} {:>8} {:>12} {:>12.0f}   (serialized payload, no RTPS/UDP "
             "headers)\n", "total", "", "", "", total);
}

}  // namespace

int MeasureBandwidth(const ConsoleOptions& o, std::ostream& out) {
  Session s = Join(o);
  runtime::Executor ex;
  // Discovery first, so that every topic with a writer is subscribed from the start.
  ex.Spin(runtime::KeepRunning(), runtime::Executor::Clock::now() +
                                      std::chrono::duration_cast<runtime::Executor::Clock::duration>(
                                          std::chrono::duration<double>(o.wait_s)));
  std::map<std::string, Traffic> traffic;
  std::vector<std::unique_ptr<runtime::RawReader>> readers;
  for (const auto& t : runtime::Summarise(s.listener->Endpoints())) {
    const MessageType* type = FindMessageType(t.type);
    if (t.writers == 0 || type == nullptr) continue;
    Traffic& counted = traffic[t.topic];
    readers.push_back(ReadRaw(s, ex, t.topic, *type,
                              [&counted](const runtime::RawSample& m, const runtime::RawSampleInfo&) {
                                counted.samples++;
                                counted.bytes += m.data.size();
                              }));
  }
  const auto begin = runtime::Executor::Clock::now();
  ex.Spin(runtime::KeepRunning(),
          begin + std::chrono::duration_cast<runtime::Executor::Clock::duration>(
                      std::chrono::duration<double>(o.timeout_s > 0.0 ? o.timeout_s : 10.0)));
  readers.clear();
  // The time really measured (Ctrl-C ends the window early).
  const double window_s = std::max(
      1e-3, std::chrono::duration<double>(runtime::Executor::Clock::now() - begin).count());
  PrintBandwidth(traffic, window_s, o.json, out);
  return 0;
}

void PrintTopicTable(const std::vector<runtime::TopicSummary>& topics, std::ostream& out) {
  fmt::print(out, "{:<26} {:<36} {:>2} {:>2}  {:<11} {:<15} {:<11} {:<8} {:<9} {}\n", "TOPIC",
             "TYPE", "W", "R", "RELIABILITY", "DURABILITY", "HISTORY", "DEADLINE", "LIVELINESS",
             "PROFILE");
  for (const auto& t : topics) {
    fmt::print(out, "{:<26} {:<36} {:>2} {:>2}  {:<11} {:<15} {:<11} {:<8} {:<9} {}{}\n",
               t.topic, t.type, t.writers, t.readers, t.reliability, t.durability, t.history,
               Seconds(t.deadline_s), Seconds(t.liveliness_lease_s),
               t.profile.empty() ? "-" : t.profile, t.mixed_qos ? " (endpoints differ)" : "");
  }
  fmt::print(out, "{} topics\n", topics.size());
}

int ListTopics(const ConsoleOptions& o, std::ostream& out) {
  Session s = Join(o);
  // Discovery is asynchronous: listen for the configured time, then report what was seen.
  runtime::Executor ex;
  std::atomic<bool>& running = runtime::KeepRunning();
  ex.Spin(running, runtime::Executor::Clock::now() +
                       std::chrono::duration_cast<runtime::Executor::Clock::duration>(
                           std::chrono::duration<double>(o.wait_s)));
  const auto topics = runtime::Summarise(s.listener->Endpoints());
  if (o.json) {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& t : topics) {
      list.push_back({{"topic", t.topic}, {"type", t.type}, {"writers", t.writers},
                      {"readers", t.readers}, {"reliability", t.reliability},
                      {"durability", t.durability}, {"history", t.history},
                      {"deadline_s", t.deadline_s}, {"liveliness_lease_s", t.liveliness_lease_s},
                      {"profile", t.profile}});
    }
    out << list.dump(2) << '\n';
  } else {
    PrintTopicTable(topics, out);
  }
  return 0;
}

namespace {

// Refuses a topic that is not StickRep's, naming the close ones.
void CheckTopicName(const Session& s, const std::string& topic) {
  if (s.participant->catalog().HasTopic(topic)) return;
  std::vector<std::string> known;
  for (const auto& [name, stream] : s.participant->catalog().streams()) known.push_back(name);
  const auto close = CloseNames(topic, known);
  std::string hint;
  for (const auto& c : close) hint += (hint.empty() ? "; did you mean: " : ", ") + c;
  throw InputError(s.system.qos_file, 0, "qos.streams",
                   "'" + topic + "' is not a StickRep topic (not in the QoS catalogue)" + hint);
}

// The type of `topic` as its writers announce it in discovery; nullptr (said on stderr) when
// no writer appears within the timeout or the type is not one this console knows.
const MessageType* WriterType(const Session& s, const std::string& topic, double timeout_s) {
  std::string type;
  const bool found = runtime::WaitFor(
      [&] {
        for (const auto& e : s.listener->Endpoints()) {
          if (e.topic == topic && e.is_writer) type = e.type;
        }
        return !type.empty() || !runtime::KeepRunning().load();
      },
      timeout_s > 0.0 ? timeout_s : 1e9);
  if (!found || type.empty()) {
    if (runtime::KeepRunning().load()) {
      fmt::print(stderr, "no writer of {} appeared within {:g} s\n", topic, timeout_s);
    }
    return nullptr;
  }
  const MessageType* support = FindMessageType(type);
  if (support == nullptr) {
    fmt::print(stderr, "{} carries {}, a type this console does not know\n", topic, type);
  }
  return support;
}

// `--field a.b.0`: that member of a sample's JSON form; throws InputError when absent.
nlohmann::json Field(const nlohmann::json& sample, const std::string& path) {
  const nlohmann::json* at = &sample;
  std::size_t begin = 0;
  while (begin <= path.size()) {
    const std::size_t dot = std::min(path.find('.', begin), path.size());
    const std::string key = path.substr(begin, dot - begin);
    if (at->is_object() && at->contains(key)) {
      at = &(*at)[key];
    } else if (at->is_array() && !key.empty() &&
               key.find_first_not_of("0123456789") == std::string::npos &&
               std::stoul(key) < at->size()) {
      at = &(*at)[std::stoul(key)];
    } else {
      std::string members;
      if (at->is_object()) {
        for (const auto& [k, v] : at->items()) members += (members.empty() ? "" : ", ") + k;
      }
      throw InputError("--field", 0, path,
                       "no member '" + key + "'" + (members.empty() ? "" : "; there are: " + members));
    }
    begin = dot + 1;
  }
  return *at;
}

}  // namespace

int EchoTopic(const ConsoleOptions& o, const std::string& topic, std::ostream& out) {
  Session s = Join(o);
  CheckTopicName(s, topic);
  // The type comes from discovery, so wait for a writer to announce it.
  const MessageType* support = WriterType(s, topic, o.timeout_s);
  if (support == nullptr) return 1;
  runtime::Executor ex;
  int printed = 0;
  auto reader = ReadRaw(s, ex, topic, *support,
                        [&](const runtime::RawSample& m, const runtime::RawSampleInfo&) {
                          if (o.count > 0 && printed >= o.count) return;
                          try {
                            const nlohmann::json j = EchoForm(
                                support->name, support->decode_json(m.data.data(), m.data.size()));
                            out << (o.field.empty() ? j : Field(j, o.field)).dump() << '\n'
                                << std::flush;
                            printed++;
                          } catch (const PayloadError& e) {
                            fmt::print(stderr, "{}: a sample dropped: {}\n", topic, e.what());
                          }
                        });
  const auto until = o.timeout_s > 0.0
                         ? runtime::Executor::Clock::now() +
                               std::chrono::duration_cast<runtime::Executor::Clock::duration>(
                                   std::chrono::duration<double>(o.timeout_s))
                         : runtime::Executor::Clock::time_point::max();
  while (runtime::KeepRunning().load() && runtime::Executor::Clock::now() < until &&
         (o.count == 0 || printed < o.count)) {
    ex.SpinOnce(std::chrono::milliseconds(50));
  }
  reader.reset();
  if (o.count > 0 && printed < o.count) {
    if (runtime::KeepRunning().load()) {
      fmt::print(stderr, "{} of {} sample(s) of {} within {:g} s\n", printed, o.count, topic,
                 o.timeout_s);
      return 1;
    }
    return 0;  // Ctrl-C
  }
  return 0;
}

namespace {

// One report line of `hz` or `delay` (JSON with --json).
void PrintWindow(const ConsoleOptions& o, const std::string& topic, TopicStat stat,
                 const TopicWindow& w, std::ostream& out) {
  if (stat == TopicStat::kRate) {
    const Spread p = w.Period();
    const double rate = p.mean > 0.0 ? 1.0 / p.mean : 0.0;
    if (o.json) {
      out << nlohmann::json{{"topic", topic}, {"rate_hz", rate}, {"period_min_s", p.min},
                            {"period_max_s", p.max}, {"period_std_s", p.stddev},
                            {"window", p.n + 1}, {"samples", w.total()}}.dump()
          << '\n' << std::flush;
    } else {
      fmt::print(out, "{}: average rate {:.3f} Hz; period min {:.4f} s, max {:.4f} s, std {:.5f} s "
                 "(window {}, {} samples)\n", topic, rate, p.min, p.max, p.stddev, p.n + 1,
                 w.total());
    }
    return;
  }
  const Spread d = w.DelayMs();
  if (o.json) {
    out << nlohmann::json{{"topic", topic}, {"delay_mean_ms", d.mean}, {"delay_min_ms", d.min},
                          {"delay_max_ms", d.max}, {"delay_std_ms", d.stddev}, {"window", d.n},
                          {"samples", w.total()}}.dump()
        << '\n' << std::flush;
  } else {
    fmt::print(out, "{}: source timestamp to reception mean {:.3f} ms; min {:.3f}, max {:.3f}, "
               "std {:.3f} ms (window {}, {} samples)\n", topic, d.mean, d.min, d.max, d.stddev,
               d.n, w.total());
  }
}

}  // namespace

int WatchTopic(const ConsoleOptions& o, const std::string& topic, TopicStat stat,
               std::ostream& out) {
  Session s = Join(o);
  CheckTopicName(s, topic);
  const double timeout_s = o.timeout_s > 0.0 ? o.timeout_s : 10.0;
  const MessageType* support = WriterType(s, topic, timeout_s);
  if (support == nullptr) return 1;
  runtime::Executor ex;
  TopicWindow window(o.window);
  auto reader = ReadRaw(s, ex, topic, *support,
                        [&](const runtime::RawSample& m, const runtime::RawSampleInfo& i) {
                          window.Add(i.source_ns, i.reception_ns, m.data.size());
                        });
  using Clock = runtime::Executor::Clock;
  const auto start = Clock::now();
  const auto seconds = [&](double s) {
    return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
  };
  const auto until = o.duration_s > 0.0 ? start + seconds(o.duration_s) : Clock::time_point::max();
  auto next_report = start + seconds(1.0);
  std::uint64_t reported = 0;
  while (runtime::KeepRunning().load() && Clock::now() < until) {
    ex.SpinOnce(std::chrono::milliseconds(20));
    if (window.total() == 0 && Clock::now() > start + seconds(timeout_s)) {
      fmt::print(stderr, "{}: a writer but no sample within {:g} s\n", topic, timeout_s);
      return 1;
    }
    if (Clock::now() >= next_report) {
      next_report += seconds(1.0);
      if (window.total() > reported && (stat == TopicStat::kDelay || window.total() > 1)) {
        PrintWindow(o, topic, stat, window, out);
        reported = window.total();
      }
    }
  }
  reader.reset();
  if (window.total() == 0) {
    fmt::print(stderr, "{}: no sample received\n", topic);
    return runtime::KeepRunning().load() ? 1 : 0;
  }
  PrintWindow(o, topic, stat, window, out);
  return 0;
}

namespace {

// Each process's latest heartbeat (system/status is transient-local, so a console that
// joins late gets them at once), read for `listen_s`.
std::map<std::string, msgs::ComponentStatus> Heartbeats(Session& s, runtime::Executor& ex,
                                                         double listen_s) {
  std::map<std::string, msgs::ComponentStatus> latest;
  runtime::Reader<msgs::ComponentStatusPubSubType> status(
      *s.participant, ex, "system/status",
      [&](const msgs::ComponentStatus& m) { latest[m.component_name()] = m; });
  ex.Spin(runtime::KeepRunning(),
          runtime::Executor::Clock::now() +
              std::chrono::duration_cast<runtime::Executor::Clock::duration>(
                  std::chrono::duration<double>(listen_s)));
  return latest;
}

// "stickrep-landmark" -> the host its heartbeat names.
std::string HostOf(const std::string& participant,
                   const std::map<std::string, msgs::ComponentStatus>& heartbeats) {
  const std::string prefix = "stickrep-";
  const std::string name =
      participant.rfind(prefix, 0) == 0 ? participant.substr(prefix.size()) : participant;
  const auto h = heartbeats.find(name);
  return h == heartbeats.end() ? "?" : h->second.host();
}

}  // namespace

int InfoTopic(const ConsoleOptions& o, const std::string& topic, bool verbose, std::ostream& out) {
  Session s = Join(o);
  CheckTopicName(s, topic);
  runtime::Executor ex;
  const auto heartbeats = Heartbeats(s, ex, o.wait_s);
  std::vector<runtime::DiscoveredEndpoint> endpoints;
  for (const auto& e : s.listener->Endpoints()) {
    if (e.topic == topic) endpoints.push_back(e);
  }
  std::sort(endpoints.begin(), endpoints.end(), [](const auto& a, const auto& b) {
    return std::tie(b.is_writer, a.participant) < std::tie(a.is_writer, b.participant);
  });
  if (o.json) {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& e : endpoints) {
      list.push_back({{"role", e.is_writer ? "writer" : "reader"}, {"process", e.participant},
                      {"host", HostOf(e.participant, heartbeats)}, {"type", e.type},
                      {"reliability", e.reliability}, {"durability", e.durability},
                      {"history", runtime::UserDataField(e.user_data, "history")},
                      {"deadline_s", e.deadline_s}, {"liveliness_lease_s", e.liveliness_lease_s},
                      {"profile", runtime::UserDataField(e.user_data, "profile")},
                      {"guid", e.guid}});
    }
    out << nlohmann::json{{"topic", topic}, {"endpoints", list}}.dump(2) << '\n';
    return 0;
  }
  fmt::print(out, "{}: {} writers, {} readers\n", topic,
             std::count_if(endpoints.begin(), endpoints.end(), [](const auto& e) { return e.is_writer; }),
             std::count_if(endpoints.begin(), endpoints.end(), [](const auto& e) { return !e.is_writer; }));
  fmt::print(out, "{:<7} {:<24} {:<10} {:<11} {:<15} {:<11} {:<8} {:<9} {:<13}{}\n", "ROLE",
             "PROCESS", "HOST", "RELIABILITY", "DURABILITY", "HISTORY", "DEADLINE", "LIVELINESS",
             "PROFILE", verbose ? " GUID / TYPE" : "");
  for (const auto& e : endpoints) {
    const std::string history = runtime::UserDataField(e.user_data, "history");
    const std::string profile = runtime::UserDataField(e.user_data, "profile");
    fmt::print(out, "{:<7} {:<24} {:<10} {:<11} {:<15} {:<11} {:<8} {:<9} {:<13}{}\n",
               e.is_writer ? "writer" : "reader", e.participant.empty() ? "?" : e.participant,
               HostOf(e.participant, heartbeats), e.reliability, e.durability,
               history.empty() ? "?" : history, Seconds(e.deadline_s),
               Seconds(e.liveliness_lease_s), profile.empty() ? "-" : profile,
               verbose ? " " + e.guid + " " + e.type : "");
  }
  return 0;
}

int ShowStatus(const ConsoleOptions& o, std::ostream& out) {
  Session s = Join(o);
  runtime::Executor ex;
  std::map<std::string, std::pair<msgs::ComponentStatus, int64_t>> latest;  // with reception
  runtime::Reader<msgs::ComponentStatusPubSubType> status(
      *s.participant, ex, "system/status", [&](const msgs::ComponentStatus& m) {
        latest[m.component_name()] = {m, runtime::WallClockNowNs()};
      });
  using Clock = runtime::Executor::Clock;
  const auto seconds = [](double v) {
    return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(v));
  };
  const auto start = Clock::now();
  const auto until = o.duration_s > 0.0 ? start + seconds(o.duration_s) : Clock::time_point::max();
  const double timeout_s = o.timeout_s > 0.0 ? o.timeout_s : 10.0;
  do {
    ex.Spin(runtime::KeepRunning(), Clock::now() + seconds(std::max(1.0, o.wait_s)));
    // Until the first heartbeat, up to the timeout. (A `continue` here would test the loop's
    // condition: a one-shot status ended at once, printing nothing, when discovery took
    // longer than the first wait.)
    while (latest.empty() && runtime::KeepRunning().load() &&
           Clock::now() - start < seconds(timeout_s)) {
      ex.Spin(runtime::KeepRunning(), Clock::now() + seconds(0.1));
    }
    if (latest.empty()) {
      fmt::print(stderr, "no process heartbeat on system/status within {:g} s\n", timeout_s);
      return 1;
    }
    const int64_t now = runtime::WallClockNowNs();
    nlohmann::json rows = nlohmann::json::array();
    if (!o.json) {
      fmt::print(out, "{:<14} {:<10} {:<22} {:>7} {:>10} {:>10} {:>8}  {}\n", "PROCESS", "HOST",
                 "STATE", "AGE S", "IN", "OUT", "DROPPED", "MESSAGE");
    }
    for (const auto& [name, entry] : latest) {
      const auto& [m, received_ns] = entry;
      const double age_s = (now - received_ns) * 1e-9;
      if (o.json) {
        rows.push_back({{"process", name},
                        {"host", m.host()},
                        {"state", msgs::EnumName(m.state())},
                        {"heartbeat_age_s", age_s}, {"samples_in", m.samples_in()},
                        {"samples_out", m.samples_out()},
                        {"samples_dropped", m.samples_dropped()}, {"message", m.message()}});
      } else {
        fmt::print(out, "{:<14} {:<10} {:<22} {:>7.1f} {:>10} {:>10} {:>8}  {}\n", name, m.host(),
                   msgs::EnumName(m.state()), age_s, m.samples_in(), m.samples_out(),
                   m.samples_dropped(), m.message());
      }
    }
    if (o.json) out << rows.dump() << '\n';
    out << std::flush;
  } while (o.count != 1 && runtime::KeepRunning().load() && Clock::now() < until);
  return 0;
}

namespace {

// Reads every timed topic (a deadline or a liveliness lease in the catalogue) that has a
// writer, with the catalogue's QoS, for `watch_s`: the deadlines DDS reports missed and the
// writers whose liveliness it reports lost. A writer of a topic with a lease that sends
// nothing for longer than the lease is counted as lost too: Fast DDS 2.9 asserts the
// liveliness of every AUTOMATIC writer of a reader while any one of them is alive
// (eProsima/Fast-DDS#4373, fixed after 2.9), so one dead heartbeat writer among seven goes
// unreported by DDS itself.
// One timed topic under watch: the reader, and how long each writer stayed silent.
struct WatchedTopic {
  struct Silence {
    int64_t last_ns = 0;
    int64_t longest_ns = 0;
  };
  TimelinessWatch watch;
  std::vector<std::string> writer_guids;
  std::map<std::string, Silence> silence;  // by writer GUID
  std::unique_ptr<runtime::RawReader> reader;
};

// A reader of `t` with its catalogued QoS when that QoS has a deadline or a lease; nullptr
// for any other topic.
std::unique_ptr<WatchedTopic> WatchTopic(Session& s, runtime::Executor& ex,
                                         const runtime::TopicSummary& t,
                                         const std::vector<runtime::DiscoveredEndpoint>& endpoints,
                                         double watch_s, int64_t begin_ns) {
  const MessageType* type = FindMessageType(t.type);
  if (t.writers == 0 || type == nullptr || !s.participant->catalog().HasTopic(t.topic)) {
    return nullptr;
  }
  const runtime::QosProfile qos = s.participant->catalog().ForTopic(t.topic);
  if (qos.deadline_s <= 0.0 && qos.liveliness_lease_s <= 0.0) return nullptr;
  auto w = std::make_unique<WatchedTopic>();
  w->watch = {t.topic, qos.deadline_s, qos.liveliness_lease_s, watch_s, {}, 0, {}, 0};
  for (const auto& e : endpoints) {
    if (e.topic != t.topic || !e.is_writer) continue;
    w->watch.writers.push_back(e.participant.empty() ? e.guid : e.participant);
    w->writer_guids.push_back(e.guid);
  }
  WatchedTopic* into = w.get();
  w->reader = std::make_unique<runtime::RawReader>(
      *s.participant, ex, t.topic, type->make_support, qos,
      [into, begin_ns](const runtime::RawSample&, const runtime::RawSampleInfo& i) {
        WatchedTopic::Silence& q = into->silence[i.writer_guid];
        q.longest_ns = std::max(q.longest_ns, i.reception_ns - (q.last_ns ? q.last_ns : begin_ns));
        q.last_ns = i.reception_ns;
      });
  return w;
}

// What DDS reported, and the writers silent for longer than the lease, by process name.
TimelinessWatch Conclude(WatchedTopic& w, int64_t begin_ns, int64_t end_ns,
                         const std::function<std::string(const std::string&)>& name_of) {
  TimelinessWatch t = w.watch;
  t.deadlines_missed = w.reader->deadlines_missed();
  t.alive_writers_at_end = w.reader->alive_writers();
  for (const std::string& guid : w.reader->writers_lost()) t.writers_lost.push_back(name_of(guid));
  const int64_t lease_ns = static_cast<int64_t>(t.lease_s * 1e9);
  for (const std::string& guid : w.writer_guids) {
    const WatchedTopic::Silence q = w.silence[guid];
    const int64_t longest = std::max(q.longest_ns, end_ns - (q.last_ns ? q.last_ns : begin_ns));
    const std::string name = name_of(guid);
    if (lease_ns > 0 && longest > lease_ns &&
        std::find(t.writers_lost.begin(), t.writers_lost.end(), name) == t.writers_lost.end()) {
      t.writers_lost.push_back(name);
    }
  }
  return t;
}

std::vector<TimelinessWatch> WatchTimedTopics(Session& s, double watch_s) {
  const auto endpoints = s.listener->Endpoints();
  runtime::Executor ex;
  const int64_t begin_ns = runtime::WallClockNowNs();
  std::vector<std::unique_ptr<WatchedTopic>> watched;
  for (const auto& t : runtime::Summarise(endpoints)) {
    if (auto w = WatchTopic(s, ex, t, endpoints, watch_s, begin_ns)) watched.push_back(std::move(w));
  }
  if (watched.empty()) return {};
  ex.Spin(runtime::KeepRunning(),
          runtime::Executor::Clock::now() +
              std::chrono::duration_cast<runtime::Executor::Clock::duration>(
                  std::chrono::duration<double>(watch_s)));
  const int64_t end_ns = runtime::WallClockNowNs();
  std::map<std::string, std::string> names;  // writer GUID -> process
  for (const auto& e : s.listener->Endpoints()) names[e.guid] = e.participant;
  const auto name_of = [&](const std::string& guid) {
    const auto it = names.find(guid);
    return it == names.end() || it->second.empty() ? guid : it->second;
  };
  std::vector<TimelinessWatch> out;
  for (auto& w : watched) out.push_back(Conclude(*w, begin_ns, end_ns, name_of));
  return out;
}

}  // namespace

int Doctor(const ConsoleOptions& o, std::ostream& out) {
  Session s = Join(o);
  runtime::Executor ex;
  ex.Spin(runtime::KeepRunning(),
          runtime::Executor::Clock::now() +
              std::chrono::duration_cast<runtime::Executor::Clock::duration>(
                  std::chrono::duration<double>(o.wait_s)));
  const auto endpoints = s.listener->Endpoints();
  auto findings = Diagnose(endpoints);
  const double watch_s = o.duration_s > 0.0 ? o.duration_s : 3.0;
  for (Finding& f : DiagnoseTimeliness(WatchTimedTopics(s, watch_s))) {
    findings.push_back(std::move(f));
  }
  const bool broken = std::any_of(findings.begin(), findings.end(), IsFault);
  if (o.json) {
    nlohmann::json list = nlohmann::json::array();
    for (const Finding& f : findings) {
      list.push_back({{"topic", f.topic}, {"problem", f.problem}, {"policy", f.policy},
                      {"writer", f.writer}, {"reader", f.reader}, {"detail", f.detail}});
    }
    out << nlohmann::json{{"endpoints", endpoints.size()}, {"findings", list}}.dump(2) << '\n';
    return broken ? 1 : 0;
  }
  fmt::print(out, "{} endpoints on domain {}; {} findings\n", endpoints.size(),
             s.system.domain_id, findings.size());
  for (const Finding& f : findings) {
    fmt::print(out, "{:<17} {:<26} {}{}{}{}\n", f.problem, f.topic,
               f.policy.empty() ? "" : "policy " + f.policy + "; ",
               f.writer.empty() ? "" : "writer " + f.writer,
               !f.writer.empty() && !f.reader.empty() ? "; " : "",
               f.reader.empty() ? "" : "reader " + f.reader);
    if (f.problem == "missed deadline" || f.problem == "lost liveliness") {
      fmt::print(out, "{:<17} {}\n", "", f.detail);
    }
  }
  if (endpoints.empty()) {
    fmt::print(stderr, "no endpoint on domain {} within {:g} s\n", s.system.domain_id, o.wait_s);
    return 1;
  }
  return broken ? 1 : 0;
}

int SendGoal(const ConsoleOptions& o, const std::string& goal_id, const std::string& target,
             std::ostream& out) {
  Session s = Join(o);
  runtime::Executor ex;
  std::optional<msgs::MissionGoalResult> result;
  runtime::Reader<msgs::MissionGoalResultPubSubType> results(
      *s.participant, ex, "mission/goal_result", [&](const msgs::MissionGoalResult& r) {
        if (r.goal_id() == goal_id && r.target() == target) result = r;
      });
  runtime::Writer<msgs::MissionGoalPubSubType> goals(*s.participant, "mission/goal");
  msgs::MissionGoal g;
  g.goal_id(goal_id);
  g.target(target);
  using Clock = runtime::Executor::Clock;
  const auto until = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(
                                            o.timeout_s > 0.0 ? o.timeout_s : 10.0));
  // Sent once both sides have matched (the goal and its result are reliable); again after
  // 2 s without an answer, in case the executive's reader was still being matched.
  auto next_send = Clock::now();
  while (!result && runtime::KeepRunning().load() && Clock::now() < until) {
    if (Clock::now() >= next_send && goals.counters().matched.load() > 0 &&
        results.counters().matched.load() > 0) {
      goals.Publish(g, runtime::WallClockNowNs());
      next_send = Clock::now() + std::chrono::seconds(2);
    }
    ex.SpinOnce(std::chrono::milliseconds(50));
  }
  if (!result) {
    fmt::print(out, "goal '{}': no answer from an executive\n", goal_id);
    return 1;
  }
  if (o.json) {
    out << ToJson(*result).dump() << '\n';
  } else {
    fmt::print(out, "goal '{}' ({}): {}: {}\n", result->goal_id(), result->target(),
               result->accepted() ? "accepted" : "refused", result->reason());
  }
  return result->accepted() ? 0 : 1;
}

}  // namespace stickrep::console
