#pragma once

// stickrep-bag: what is in a recording, its samples as JSON lines, and a check that every
// payload deserializes to its type. No DDS traffic: types are decoded with their support
// classes (console/message_types.h).

#include <cstdint>
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

namespace stickrep::recording {

struct BagTopicInfo {
  std::string name;
  std::string type;
  std::int64_t count = 0;
  double rate_hz = 0.0;        // samples over the recording's duration
  std::uint64_t bytes = 0;
  std::string offered_qos;     // JSON text, as recorded
};

struct BagInfo {
  std::string path;
  std::uint64_t file_bytes = 0;
  double duration_s = 0.0;     // first to last sample
  std::int64_t first_ns = 0, last_ns = 0;
  std::int64_t messages = 0;
  std::map<std::string, std::string> metadata;  // short entries (files' texts left out)
  std::vector<BagTopicInfo> topics;
};

// Throws InputError for a file that is not a readable recording.
BagInfo InspectBag(const std::string& path);
void PrintBagInfo(const BagInfo& info, std::ostream& out);
void PrintBagInfoJson(const BagInfo& info, std::ostream& out);

// One JSON line per sample of `topic` (the console's JSON form), in timestamp order.
// Throws InputError for an unknown topic (naming the recorded ones) or an unknown type;
// returns the number of samples that did not deserialize (each reported on `err`).
std::int64_t ExportTopic(const std::string& path, const std::string& topic, std::ostream& out,
                         std::ostream& err);

// Deserializes every payload with its type. Returns the number of bad samples plus topics
// of unknown types; prints a line per topic and one per bad sample (the first 20).
std::int64_t CheckBag(const std::string& path, std::ostream& out);

}  // namespace stickrep::recording
