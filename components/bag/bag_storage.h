#pragma once

// Recordings of StickRep streams in one SQLite file, in the layout of rosbag2's sqlite3
// storage: topics(id, name, type, serialization_format, offered_qos_profiles), messages(id,
// topic_id, timestamp, data) with an index on timestamp, plus the reception time of each
// sample and a metadata table (key, value). Payloads are stored as given (serialized CDR).
// No DDS: the recorder and the replayer wrap this.

#include <sqlite3.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <limits>
#include <utility>
#include <map>
#include <string>
#include <vector>

namespace stickrep::bag {

struct TopicInfo {
  std::int64_t id = 0;
  std::string name;
  std::string type;
  std::string serialization_format = "cdr";
  std::string offered_qos_profiles;  // the writers' QoS as seen in discovery (JSON text)
};

struct Message {
  std::int64_t topic_id = 0;
  std::int64_t timestamp_ns = 0;  // the writer's source timestamp
  std::int64_t received_ns = 0;   // when the recorder received it
  std::vector<std::uint8_t> data;
};

// Writes a new recording. The journal is WAL; samples are committed in transactions of at
// most `batch_s` of wall time, so a process killed outright loses at most the open batch
// and leaves a file that opens. Throws InputError when the file cannot be created (it must
// not exist) or a write fails (e.g. the disk is full): what was committed stays.
class BagWriter {
 public:
  explicit BagWriter(const std::string& path, double batch_s = 0.1);
  ~BagWriter();
  BagWriter(const BagWriter&) = delete;
  BagWriter& operator=(const BagWriter&) = delete;

  // A topic's row; its id for Write().
  std::int64_t AddTopic(const TopicInfo& topic);
  // Replaces a topic's offered_qos_profiles (the writers' QoS, once discovery has seen them).
  void SetTopicQos(std::int64_t topic_id, const std::string& offered_qos_profiles);
  void Write(std::int64_t topic_id, std::int64_t timestamp_ns, std::int64_t received_ns,
             const std::uint8_t* data, std::size_t size);
  void SetMetadata(const std::string& key, const std::string& value);
  // Caps the file at about `bytes` (SQLite's max_page_count): past it a write fails as on a
  // full disk. For testing that case; 0 leaves the file unbounded.
  void SetSizeLimit(std::int64_t bytes);
  // Commits the open batch.
  void Flush();
  std::int64_t written() const { return written_; }

 private:
  void Exec(const std::string& sql);
  void Fail(const std::string& what) const;
  void BeginIfNeeded();

  std::string path_;
  sqlite3* db_ = nullptr;
  sqlite3_stmt* insert_ = nullptr;
  double batch_s_;
  bool in_batch_ = false;
  std::chrono::steady_clock::time_point batch_start_;
  std::int64_t written_ = 0;
};

// Reads a recording. Throws InputError naming the file for one that is not SQLite, is
// truncated or damaged, or is an SQLite database without StickRep's tables.
class BagReader {
 public:
  explicit BagReader(const std::string& path);
  ~BagReader();
  BagReader(const BagReader&) = delete;
  BagReader& operator=(const BagReader&) = delete;

  const std::vector<TopicInfo>& topics() const { return topics_; }
  std::map<std::string, std::string> Metadata() const;
  // Samples per topic id.
  std::map<std::int64_t, std::int64_t> Counts() const;
  // Every message with from_ns <= timestamp <= to_ns in timestamp order (ties by id), to
  // `fn`; stops early when it returns false.
  void ForEach(const std::function<bool(const Message&)>& fn,
               std::int64_t from_ns = std::numeric_limits<std::int64_t>::min(),
               std::int64_t to_ns = std::numeric_limits<std::int64_t>::max()) const;
  // The first and last message timestamps; {0, 0} for a recording without messages.
  std::pair<std::int64_t, std::int64_t> TimeRange() const;
  const std::string& path() const { return path_; }

 private:
  void Fail(const std::string& what) const;

  std::string path_;
  sqlite3* db_ = nullptr;
  std::vector<TopicInfo> topics_;
};

}  // namespace stickrep::bag
