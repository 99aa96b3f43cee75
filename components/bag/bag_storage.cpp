#include "bag/bag_storage.h"

#include <algorithm>
#include <filesystem>

#include "common/input_error.h"

namespace stickrep::bag {

namespace {

constexpr const char* kSchema =
    "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, "
    "serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);"
    "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, "
    "timestamp INTEGER NOT NULL, data BLOB NOT NULL, received_timestamp INTEGER NOT NULL);"
    "CREATE INDEX timestamp_idx ON messages (timestamp ASC);"
    "CREATE TABLE metadata(key TEXT PRIMARY KEY, value TEXT NOT NULL);";

// A statement finalized when it goes out of scope.
struct Statement {
  sqlite3_stmt* s = nullptr;
  ~Statement() { sqlite3_finalize(s); }
};

// Closes the database a constructor opened if the constructor throws: the destructor does
// not run then, and the connection and its file would stay open.
struct CloseOnThrow {
  sqlite3*& db;
  sqlite3_stmt*& statement;  // finalized first (closing fails while one is open)
  bool constructed = false;
  ~CloseOnThrow() {
    if (constructed) return;
    sqlite3_finalize(statement);
    statement = nullptr;
    sqlite3_close(db);
    db = nullptr;
  }
};

std::string Column(sqlite3_stmt* s, int i) {
  const auto* text = sqlite3_column_text(s, i);
  return text == nullptr ? "" : reinterpret_cast<const char*>(text);
}

}  // namespace

BagWriter::BagWriter(const std::string& path, double batch_s) : path_(path), batch_s_(batch_s) {
  if (std::filesystem::exists(path)) Fail("exists already; a recording is never overwritten");
  CloseOnThrow guard{db_, insert_};
  if (sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) !=
      SQLITE_OK) {
    Fail("cannot be created");
  }
  Exec("PRAGMA journal_mode=WAL;");
  Exec("PRAGMA synchronous=NORMAL;");
  Exec(kSchema);
  if (sqlite3_prepare_v2(db_,
                         "INSERT INTO messages(topic_id, timestamp, data, received_timestamp) "
                         "VALUES(?, ?, ?, ?)",
                         -1, &insert_, nullptr) != SQLITE_OK) {
    Fail("cannot prepare the message insert");
  }
  guard.constructed = true;
}

BagWriter::~BagWriter() {
  try {
    Flush();
  } catch (...) {  // the caller flushes to see errors; a destructor must not throw
  }
  sqlite3_finalize(insert_);
  sqlite3_close(db_);
}

void BagWriter::Fail(const std::string& what) const {
  const std::string detail = db_ != nullptr ? std::string(" (") + sqlite3_errmsg(db_) + ")" : "";
  throw InputError(path_, 0, "", what + detail);
}

void BagWriter::Exec(const std::string& sql) {
  char* error = nullptr;
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &error) != SQLITE_OK) {
    const std::string message = error != nullptr ? error : "unknown error";
    sqlite3_free(error);
    throw InputError(path_, 0, "", "SQLite: " + message);
  }
}

std::int64_t BagWriter::AddTopic(const TopicInfo& topic) {
  Statement s;
  sqlite3_prepare_v2(db_,
                     "INSERT INTO topics(name, type, serialization_format, offered_qos_profiles) "
                     "VALUES(?, ?, ?, ?)",
                     -1, &s.s, nullptr);
  sqlite3_bind_text(s.s, 1, topic.name.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s.s, 2, topic.type.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s.s, 3, topic.serialization_format.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s.s, 4, topic.offered_qos_profiles.c_str(), -1, SQLITE_TRANSIENT);
  if (sqlite3_step(s.s) != SQLITE_DONE) Fail("cannot add topic " + topic.name);
  return sqlite3_last_insert_rowid(db_);
}

void BagWriter::SetTopicQos(std::int64_t topic_id, const std::string& offered_qos_profiles) {
  Statement s;
  sqlite3_prepare_v2(db_, "UPDATE topics SET offered_qos_profiles = ? WHERE id = ?", -1, &s.s,
                     nullptr);
  sqlite3_bind_text(s.s, 1, offered_qos_profiles.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_int64(s.s, 2, topic_id);
  if (sqlite3_step(s.s) != SQLITE_DONE) Fail("cannot update the QoS of topic id " + std::to_string(topic_id));
}

void BagWriter::BeginIfNeeded() {
  if (in_batch_) return;
  Exec("BEGIN;");
  in_batch_ = true;
  batch_start_ = std::chrono::steady_clock::now();
}

void BagWriter::Write(std::int64_t topic_id, std::int64_t timestamp_ns, std::int64_t received_ns,
                      const std::uint8_t* data, std::size_t size) {
  BeginIfNeeded();
  sqlite3_reset(insert_);
  sqlite3_bind_int64(insert_, 1, topic_id);
  sqlite3_bind_int64(insert_, 2, timestamp_ns);
  sqlite3_bind_blob64(insert_, 3, data, size, SQLITE_TRANSIENT);
  sqlite3_bind_int64(insert_, 4, received_ns);
  if (sqlite3_step(insert_) != SQLITE_DONE) {
    // The open batch is lost (SQLite may already have rolled it back); what was committed
    // before stays.
    const std::string why = sqlite3_errmsg(db_);
    sqlite3_exec(db_, "ROLLBACK;", nullptr, nullptr, nullptr);
    in_batch_ = false;
    throw InputError(path_, 0, "", "cannot store a sample (" + why + ")");
  }
  written_++;
  if (std::chrono::duration<double>(std::chrono::steady_clock::now() - batch_start_).count() >=
      batch_s_) {
    Flush();
  }
}

void BagWriter::SetMetadata(const std::string& key, const std::string& value) {
  Statement s;
  sqlite3_prepare_v2(db_, "INSERT OR REPLACE INTO metadata(key, value) VALUES(?, ?)", -1, &s.s,
                     nullptr);
  sqlite3_bind_text(s.s, 1, key.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s.s, 2, value.c_str(), -1, SQLITE_TRANSIENT);
  if (sqlite3_step(s.s) != SQLITE_DONE) Fail("cannot write metadata " + key);
}

void BagWriter::SetSizeLimit(std::int64_t bytes) {
  if (bytes <= 0) return;
  Statement s;
  sqlite3_prepare_v2(db_, "PRAGMA page_size", -1, &s.s, nullptr);
  const std::int64_t page = sqlite3_step(s.s) == SQLITE_ROW ? sqlite3_column_int64(s.s, 0) : 4096;
  Exec("PRAGMA max_page_count=" + std::to_string(std::max<std::int64_t>(1, bytes / page)) + ";");
}

void BagWriter::Flush() {
  if (!in_batch_) return;
  in_batch_ = false;
  char* error = nullptr;
  if (sqlite3_exec(db_, "COMMIT;", nullptr, nullptr, &error) != SQLITE_OK) {
    const std::string message = error != nullptr ? error : "unknown error";
    sqlite3_free(error);
    sqlite3_exec(db_, "ROLLBACK;", nullptr, nullptr, nullptr);
    throw InputError(path_, 0, "", "cannot commit a batch of samples (SQLite: " + message + ")");
  }
}

BagReader::BagReader(const std::string& path) : path_(path) {
  if (!std::filesystem::is_regular_file(path)) Fail("no such recording");
  sqlite3_stmt* no_statement = nullptr;
  CloseOnThrow guard{db_, no_statement};
  if (sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
    Fail("cannot be opened");
  }
  Statement s;
  if (sqlite3_prepare_v2(db_,
                         "SELECT id, name, type, serialization_format, offered_qos_profiles "
                         "FROM topics ORDER BY id",
                         -1, &s.s, nullptr) != SQLITE_OK) {
    const std::string why = sqlite3_errmsg(db_);
    Fail(why.find("no such table") != std::string::npos
             ? "an SQLite database, but not a StickRep recording (no topics table)"
             : "not a StickRep recording: " + why);
  }
  int rc;
  while ((rc = sqlite3_step(s.s)) == SQLITE_ROW) {
    topics_.push_back(TopicInfo{sqlite3_column_int64(s.s, 0), Column(s.s, 1), Column(s.s, 2),
                                Column(s.s, 3), Column(s.s, 4)});
  }
  if (rc != SQLITE_DONE) Fail(std::string("damaged: ") + sqlite3_errmsg(db_));
  guard.constructed = true;
}

BagReader::~BagReader() { sqlite3_close(db_); }

void BagReader::Fail(const std::string& what) const { throw InputError(path_, 0, "", what); }

std::map<std::string, std::string> BagReader::Metadata() const {
  std::map<std::string, std::string> out;
  Statement s;
  if (sqlite3_prepare_v2(db_, "SELECT key, value FROM metadata", -1, &s.s, nullptr) != SQLITE_OK) {
    Fail("not a StickRep recording (no metadata table)");
  }
  while (sqlite3_step(s.s) == SQLITE_ROW) out[Column(s.s, 0)] = Column(s.s, 1);
  return out;
}

std::map<std::int64_t, std::int64_t> BagReader::Counts() const {
  std::map<std::int64_t, std::int64_t> out;
  Statement s;
  if (sqlite3_prepare_v2(db_, "SELECT topic_id, COUNT(*) FROM messages GROUP BY topic_id", -1,
                         &s.s, nullptr) != SQLITE_OK) {
    Fail("not a StickRep recording (no messages table)");
  }
  while (sqlite3_step(s.s) == SQLITE_ROW) {
    out[sqlite3_column_int64(s.s, 0)] = sqlite3_column_int64(s.s, 1);
  }
  return out;
}

std::pair<std::int64_t, std::int64_t> BagReader::TimeRange() const {
  Statement s;
  if (sqlite3_prepare_v2(db_, "SELECT MIN(timestamp), MAX(timestamp) FROM messages", -1, &s.s,
                         nullptr) != SQLITE_OK) {
    Fail("not a StickRep recording (no messages table)");
  }
  if (sqlite3_step(s.s) != SQLITE_ROW) Fail(std::string("damaged: ") + sqlite3_errmsg(db_));
  return {sqlite3_column_int64(s.s, 0), sqlite3_column_int64(s.s, 1)};
}

void BagReader::ForEach(const std::function<bool(const Message&)>& fn, std::int64_t from_ns,
                        std::int64_t to_ns) const {
  Statement s;
  if (sqlite3_prepare_v2(db_,
                         "SELECT topic_id, timestamp, received_timestamp, data FROM messages "
                         "WHERE timestamp >= ? AND timestamp <= ? ORDER BY timestamp, id",
                         -1, &s.s, nullptr) != SQLITE_OK) {
    Fail("not a StickRep recording (no messages table)");
  }
  sqlite3_bind_int64(s.s, 1, from_ns);
  sqlite3_bind_int64(s.s, 2, to_ns);
  int rc;
  Message m;
  while ((rc = sqlite3_step(s.s)) == SQLITE_ROW) {
    m.topic_id = sqlite3_column_int64(s.s, 0);
    m.timestamp_ns = sqlite3_column_int64(s.s, 1);
    m.received_ns = sqlite3_column_int64(s.s, 2);
    const auto* blob = static_cast<const std::uint8_t*>(sqlite3_column_blob(s.s, 3));
    m.data.assign(blob, blob + sqlite3_column_bytes(s.s, 3));
    if (!fn(m)) return;
  }
  if (rc != SQLITE_DONE) Fail(std::string("damaged: ") + sqlite3_errmsg(db_));
}

}  // namespace stickrep::bag
