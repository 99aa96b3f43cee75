#include "recording/bag_inspect.h"

#include <fmt/format.h>
#include <fmt/ostream.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <ostream>

#include "bag/bag_storage.h"
#include "common/input_error.h"
#include "console/message_types.h"

namespace stickrep::recording {

namespace {

// The files' texts and the IDL are left out of a summary (stickrep-bag info).
bool ShortEntry(const std::string& key, const std::string&) {
  return key.rfind("idl/", 0) != 0 && key.find(".text") == std::string::npos;
}

const bag::TopicInfo& FindTopic(const bag::BagReader& reader, const std::string& topic) {
  std::string names;
  for (const auto& t : reader.topics()) {
    if (t.name == topic) return t;
    names += (names.empty() ? "" : ", ") + t.name;
  }
  throw InputError(reader.path(), 0, "--topic",
                   "'" + topic + "' is not recorded here; recorded: " + names);
}

}  // namespace

BagInfo InspectBag(const std::string& path) {
  bag::BagReader reader(path);
  BagInfo info;
  info.path = path;
  info.file_bytes = std::filesystem::file_size(path);
  for (const auto& [key, value] : reader.Metadata()) {
    if (ShortEntry(key, value)) info.metadata[key] = value;
  }
  std::map<std::int64_t, std::uint64_t> bytes;
  bool any = false;
  reader.ForEach([&](const bag::Message& m) {
    bytes[m.topic_id] += m.data.size();
    info.messages++;
    if (!any) info.first_ns = m.timestamp_ns;
    info.last_ns = m.timestamp_ns;
    any = true;
    return true;
  });
  info.duration_s = (info.last_ns - info.first_ns) * 1e-9;
  const auto counts = reader.Counts();
  for (const auto& t : reader.topics()) {
    BagTopicInfo ti;
    ti.name = t.name;
    ti.type = t.type;
    const auto c = counts.find(t.id);
    ti.count = c == counts.end() ? 0 : c->second;
    ti.rate_hz = info.duration_s > 0.0 ? ti.count / info.duration_s : 0.0;
    ti.bytes = bytes[t.id];
    ti.offered_qos = t.offered_qos_profiles;
    info.topics.push_back(ti);
  }
  return info;
}

void PrintBagInfo(const BagInfo& info, std::ostream& out) {
  fmt::print(out, "file:      {} ({:.2f} MB)\n", info.path, info.file_bytes / 1e6);
  fmt::print(out, "duration:  {:.3f} s ({} samples)\n", info.duration_s, info.messages);
  for (const char* key : {"stickrep_version", "host", "domain_id", "map_file"}) {
    const auto it = info.metadata.find(key);
    if (it != info.metadata.end()) fmt::print(out, "{:<10} {}\n", std::string(key) + ":", it->second);
  }
  fmt::print(out, "{:<28} {:<36} {:>8} {:>8} {:>12}\n", "TOPIC", "TYPE", "COUNT", "HZ", "BYTES");
  for (const auto& t : info.topics) {
    fmt::print(out, "{:<28} {:<36} {:>8} {:>8.2f} {:>12}\n", t.name, t.type, t.count, t.rate_hz,
               t.bytes);
  }
}

void PrintBagInfoJson(const BagInfo& info, std::ostream& out) {
  nlohmann::json topics = nlohmann::json::array();
  for (const auto& t : info.topics) {
    nlohmann::json qos = nlohmann::json::parse(t.offered_qos, nullptr, false);
    topics.push_back({{"name", t.name}, {"type", t.type}, {"count", t.count},
                      {"rate_hz", t.rate_hz}, {"bytes", t.bytes},
                      {"offered_qos_profiles", qos.is_discarded() ? nlohmann::json(t.offered_qos) : qos}});
  }
  const nlohmann::json j = {{"file", info.path},          {"size_bytes", info.file_bytes},
                            {"duration_s", info.duration_s}, {"first_ns", info.first_ns},
                            {"last_ns", info.last_ns},    {"messages", info.messages},
                            {"metadata", info.metadata},  {"topics", topics}};
  out << j.dump(2) << '\n';
}

std::int64_t ExportTopic(const std::string& path, const std::string& topic, std::ostream& out,
                         std::ostream& err) {
  bag::BagReader reader(path);
  const bag::TopicInfo& t = FindTopic(reader, topic);
  const console::MessageType* type = console::FindMessageType(t.type);
  if (type == nullptr) {
    throw InputError(path, 0, "topics." + topic, "type '" + t.type + "' is not one this build knows");
  }
  std::int64_t bad = 0;
  reader.ForEach([&](const bag::Message& m) {
    if (m.topic_id != t.id) return true;
    try {
      out << type->decode_json(m.data.data(), m.data.size()).dump() << '\n';
    } catch (const console::PayloadError& e) {
      bad++;
      fmt::print(err, "{}: {} sample at {} ns: {}\n", path, topic, m.timestamp_ns, e.what());
    }
    return true;
  });
  return bad;
}

std::int64_t CheckBag(const std::string& path, std::ostream& out) {
  bag::BagReader reader(path);
  std::map<std::int64_t, const console::MessageType*> types;
  std::map<std::int64_t, std::pair<std::int64_t, std::int64_t>> tally;  // good, bad
  std::int64_t problems = 0;
  for (const auto& t : reader.topics()) {
    types[t.id] = console::FindMessageType(t.type);
    if (types[t.id] == nullptr) {
      fmt::print(out, "{}: topic {}: type '{}' is not one this build knows\n", path, t.name, t.type);
      problems++;
    }
  }
  std::int64_t reported = 0;
  reader.ForEach([&](const bag::Message& m) {
    const auto type = types.find(m.topic_id);
    if (type == types.end()) {
      if (reported++ < 20) fmt::print(out, "{}: a sample of topic id {} that has no topic row\n", path, m.topic_id);
      problems++;
      return true;
    }
    if (type->second == nullptr) return true;
    try {
      type->second->decode_json(m.data.data(), m.data.size());
      tally[m.topic_id].first++;
    } catch (const console::PayloadError& e) {
      tally[m.topic_id].second++;
      problems++;
      if (reported++ < 20) {
        fmt::print(out, "{}: sample at {} ns does not deserialize as {}: {}\n", path,
                   m.timestamp_ns, type->second->name, e.what());
      }
    }
    return true;
  });
  for (const auto& t : reader.topics()) {
    const auto [good, bad] = tally[t.id];
    fmt::print(out, "{:<28} {:<36} {:>8} ok {:>6} bad\n", t.name, t.type, good, bad);
  }
  fmt::print(out, "{}: {}\n", path, problems == 0 ? "every payload deserializes to its type"
                                                   : fmt::format("{} problems", problems));
  return problems;
}

}  // namespace stickrep::recording
