#include "bag/bag_storage.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "common/input_error.h"

namespace stickrep::bag {
namespace {

// A fresh path in the test's temporary directory.
std::string TempPath(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("stickrep_bag_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::filesystem::remove(path);
  return path.string();
}

std::vector<std::uint8_t> Bytes(int n, std::uint8_t value) {
  return std::vector<std::uint8_t>(static_cast<size_t>(n), value);
}

void WriteSample(BagWriter& w, std::int64_t topic, std::int64_t t, int size) {
  const auto data = Bytes(size, static_cast<std::uint8_t>(t & 0xff));
  w.Write(topic, t, t + 5, data.data(), data.size());
}

TEST(BagStorageTest, WhatIsWrittenIsReadBackInTimestampOrder) {
  const std::string path = TempPath("round_trip.sqlite");
  {
    BagWriter w(path);
    const auto sonar = w.AddTopic({0, "robot/sonar", "stickrep::msgs::SonarScan", "cdr", "{}"});
    const auto frames = w.AddTopic({0, "device/camera/frame", "stickrep::msgs::Image", "cdr", "[]"});
    WriteSample(w, sonar, 300, 10);
    WriteSample(w, frames, 100, 250000);
    WriteSample(w, sonar, 200, 10);
    w.SetMetadata("stickrep_version", "test");
    EXPECT_EQ(w.written(), 3);
  }
  BagReader r(path);
  ASSERT_EQ(r.topics().size(), 2u);
  EXPECT_EQ(r.topics()[1].name, "device/camera/frame");
  EXPECT_EQ(r.topics()[1].offered_qos_profiles, "[]");
  EXPECT_EQ(r.Metadata().at("stickrep_version"), "test");
  EXPECT_EQ(r.Counts().at(r.topics()[0].id), 2);
  std::vector<std::int64_t> stamps;
  r.ForEach([&](const Message& m) {
    stamps.push_back(m.timestamp_ns);
    EXPECT_EQ(m.received_ns, m.timestamp_ns + 5);
    EXPECT_EQ(m.data.front(), static_cast<std::uint8_t>(m.timestamp_ns & 0xff));
    EXPECT_EQ(m.data.size(), m.timestamp_ns == 100 ? 250000u : 10u);
    return true;
  });
  EXPECT_EQ(stamps, (std::vector<std::int64_t>{100, 200, 300}));
}

TEST(BagStorageTest, AnExistingFileIsNeverOverwritten) {
  const std::string path = TempPath("exists.sqlite");
  std::ofstream(path) << "keep me";
  EXPECT_THROW(BagWriter w(path), InputError);
  std::ifstream in(path);
  std::string text;
  std::getline(in, text);
  EXPECT_EQ(text, "keep me");
}

TEST(BagStorageTest, AFileThatIsNotSqliteIsRefusedWithItsName) {
  const std::string path = TempPath("text.sqlite");
  std::ofstream(path) << "this is not a database\n";
  try {
    BagReader r(path);
    FAIL() << "a text file was opened as a recording";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("text.sqlite"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("not a StickRep recording"), std::string::npos) << e.what();
  }
}

int OpenFileDescriptors() {
  int n = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator("/proc/self/fd")) ++n;
  return n;
}

// A refused file leaves nothing open: the constructor closes the connection it opened before
// throwing (found by LeakSanitizer in the ASan unit suite: each refusal kept the connection
// and its file descriptor).
TEST(BagStorageTest, ARefusedFileIsClosedAgain) {
  const std::string path = TempPath("refused.sqlite");
  std::ofstream(path) << "this is not a database\n";
  const int before = OpenFileDescriptors();
  for (int i = 0; i < 20; ++i) {
    EXPECT_THROW(BagReader r(path), InputError);
  }
  EXPECT_EQ(OpenFileDescriptors(), before);
}

TEST(BagStorageTest, AForeignSqliteDatabaseIsRefused) {
  const std::string path = TempPath("foreign.sqlite");
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  sqlite3_exec(db, "CREATE TABLE shop(item TEXT);", nullptr, nullptr, nullptr);
  sqlite3_close(db);
  try {
    BagReader r(path);
    FAIL() << "a foreign database was opened as a recording";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no topics table"), std::string::npos) << e.what();
  }
}

TEST(BagStorageTest, AKilledWriterLosesAtMostTheOpenBatch) {
  const std::string path = TempPath("killed.sqlite");
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    BagWriter w(path, /*batch_s=*/3600.0);  // only Flush commits
    const auto topic = w.AddTopic({0, "robot/odometry", "stickrep::msgs::Odometry", "cdr", "{}"});
    for (int i = 0; i < 100; ++i) WriteSample(w, topic, i, 68);
    w.Flush();
    for (int i = 100; i < 110; ++i) WriteSample(w, topic, i, 68);
    raise(SIGKILL);  // no destructor, no flush
  }
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status));
  BagReader r(path);
  int read = 0;
  r.ForEach([&](const Message&) { return ++read > 0; });
  EXPECT_EQ(read, 100);  // the committed batch, not the open one
}

TEST(BagStorageTest, ATruncatedFileIsRefused) {
  const std::string path = TempPath("truncated.sqlite");
  {
    BagWriter w(path);
    const auto topic = w.AddTopic({0, "device/camera/frame", "stickrep::msgs::Image", "cdr", "[]"});
    for (int i = 0; i < 20; ++i) WriteSample(w, topic, i, 20000);
  }
  std::filesystem::remove(path + "-wal");
  std::filesystem::remove(path + "-shm");
  std::filesystem::resize_file(path, std::filesystem::file_size(path) / 2);
  EXPECT_THROW(
      {
        BagReader r(path);
        r.ForEach([](const Message&) { return true; });
      },
      InputError);
}

}  // namespace
}  // namespace stickrep::bag
