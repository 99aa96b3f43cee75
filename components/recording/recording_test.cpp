// The recorder, the bag tools and the replayer in one process, on a domain of the test's own:
// payloads are stored unchanged and come back unchanged; a full file keeps what it committed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include "bag/bag_storage.h"
#include "common/input_error.h"
#include "console/message_types.h"
#include "recording/bag_inspect.h"
#include "recording/recorder.h"
#include "recording/replay_session.h"
#include "recording/replayer.h"
#include "runtime/endpoint.h"
#include "runtime/test_domain.h"
#include "perceptionPubSubTypes.h"
#include "sensorsPubSubTypes.h"
#include "systemPubSubTypes.h"

namespace stickrep::recording {
namespace {

using runtime::ParticipantConfig;
using runtime::QosCatalog;

std::string TempPath(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("stickrep_recording_test_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::filesystem::remove(path);
  return path.string();
}

QosCatalog Catalog() { return QosCatalog::LoadFile(runtime::DefaultConfigDir() + "/qos.yaml"); }

RecordOptions Options(const std::string& output, double duration_s) {
  RecordOptions o;
  o.output = output;
  o.system_file = runtime::DefaultConfigDir() + "/system.yaml";
  o.domain_id = runtime::TestDomainId();
  o.duration_s = duration_s;
  return o;
}

msgs::Image Frame(int k) {
  msgs::Image img;
  img.width_px(512);
  img.height_px(480);
  img.step_bytes(512);
  img.encoding("mono8");
  img.data(std::vector<uint8_t>(512 * 480, static_cast<uint8_t>(k)));
  return img;
}

// Records for `duration_s` on a thread while `publish` runs on this one; the duration leaves
// several seconds for discovery before the samples are written.
RecordReport RecordWhile(const RecordOptions& o, const std::function<void()>& publish) {
  RecordReport report;
  std::ostringstream log;
  std::thread recorder([&] { report = Record(o, log); });
  publish();
  recorder.join();
  std::ostringstream printed;
  PrintRecordReport(report, printed);
  std::cout << log.str() << printed.str();
  return report;
}

TEST(RecordingTest, RecordsEveryTopicUnchangedAndTheToolsReadIt) {
  const std::string file = TempPath("round_trip.db3");
  runtime::Participant p(ParticipantConfig{runtime::TestDomainId(), "publisher", "", "", {}},
                         Catalog());
  // Observations are reliable (counted exactly: nothing sent after matching may be lost);
  // frames are best effort.
  runtime::Writer<msgs::LandmarkObservationPubSubType> observations(p, "perception/landmark");
  runtime::Writer<msgs::ImagePubSubType> frames(p, "device/camera/frame");
  const RecordReport report = RecordWhile(Options(file, 8.0), [&] {
    ASSERT_TRUE(observations.WaitForMatched(1, 5.0));
    ASSERT_TRUE(frames.WaitForMatched(1, 5.0));
    for (int k = 1; k <= 20; ++k) {
      msgs::LandmarkObservation o;
      o.door_class(msgs::DOOR_36);
      o.width_in(10.0 * k);
      observations.Publish(o, 1000 * k);
      if (k % 4 == 0) {
        msgs::Image img = Frame(k);
        frames.Publish(img, 1000 * k);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  });
  ASSERT_TRUE(report.failure.empty()) << report.failure;
  EXPECT_EQ(report.topics.at("perception/landmark").received, 20u);
  EXPECT_EQ(report.topics.at("perception/landmark").stored, 20u);
  EXPECT_EQ(report.topics.at("perception/landmark").lost, 0u);
  const TopicTally& frames_tally = report.topics.at("device/camera/frame");
  EXPECT_GT(frames_tally.stored, 0u);
  EXPECT_EQ(frames_tally.stored, frames_tally.received);
  // Every catalogued topic was subscribed; only the two that carried samples are in the file.
  EXPECT_EQ(report.topics.at("localization/pose").received, 0u);

  const BagInfo info = InspectBag(file);
  ASSERT_EQ(info.topics.size(), 2u);
  EXPECT_EQ(info.messages, static_cast<std::int64_t>(20 + frames_tally.stored));
  EXPECT_EQ(info.metadata.count("stickrep_version"), 1u);
  EXPECT_EQ(info.metadata.count("counts"), 1u);
  bag::BagReader reader(file);
  EXPECT_NE(reader.Metadata().at("idl/perception.idl").find("struct LandmarkObservation"),
            std::string::npos);
  EXPECT_NE(reader.Metadata().at("map_file.text").find("rings"), std::string::npos);
  for (const auto& t : reader.topics()) {
    EXPECT_NE(t.offered_qos_profiles.find("reliability"), std::string::npos) << t.name;
  }

  std::ostringstream check;
  EXPECT_EQ(CheckBag(file, check), 0) << check.str();
  std::ostringstream lines, err;
  EXPECT_EQ(ExportTopic(file, "perception/landmark", lines, err), 0);
  std::istringstream in(lines.str());
  std::string first;
  std::getline(in, first);
  const auto j = nlohmann::json::parse(first);
  EXPECT_EQ(j["header"]["sequence_number"], 1);
  EXPECT_DOUBLE_EQ(j["width_in"].get<double>(), 10.0);
  EXPECT_EQ(j["door_class"], "DOOR_36");
  EXPECT_THROW(ExportTopic(file, "robot/sonar", lines, err), InputError);
}

// A recording made by hand: 30 echoes 10 ms apart (stamps and sequence numbers k = 1..30),
// serialized with the real type.
void WriteEchoes(const std::string& file) {
  {
    bag::BagWriter w(file);
    const auto id = w.AddTopic({0, "device/sonar/echo", "stickrep::msgs::SonarEcho", "cdr",
                                R"([{"reliability":"best_effort","durability":"volatile",)"
                                R"("history":"keep_last 5","profile":"sensor"}])"});
    msgs::SonarEchoPubSubType support;
    for (int k = 1; k <= 30; ++k) {
      msgs::SonarEcho e;
      e.header().stamp_ns(k * 10'000'000LL);
      e.header().sequence_number(k);
      std::array<float, 24> r;
      r.fill(static_cast<float>(k));
      e.range_in(r);
      eprosima::fastrtps::rtps::SerializedPayload_t payload(
          support.getSerializedSizeProvider(&e)());
      ASSERT_TRUE(support.serialize(&e, &payload));
      w.Write(id, k * 10'000'000LL, 0, payload.data, payload.length);
    }
  }
}

TEST(RecordingTest, ReplayPublishesTheRecordedPayloadsInOrder) {
  const std::string file = TempPath("replay.db3");
  WriteEchoes(file);
  runtime::Participant listener(
      ParticipantConfig{runtime::TestDomainId(), "listener", "", "", {}}, Catalog());
  runtime::Participant replaying(
      ParticipantConfig{runtime::TestDomainId(), "replay", "", "", {}}, Catalog());
  runtime::Executor ex;
  std::vector<uint32_t> sequence;
  std::vector<int64_t> stamps;
  // A keep-last-5 best-effort reader, as the sonar process has: drained as samples come.
  runtime::Reader<msgs::SonarEchoPubSubType> reader(listener, ex, "device/sonar/echo",
                                                    [&](const msgs::SonarEcho& e) {
                                                      sequence.push_back(e.header().sequence_number());
                                                      stamps.push_back(e.header().stamp_ns());
                                                    });
  runtime::Executor replay_ex;
  ReplayOptions o;
  o.file = file;
  o.rate = 2.0;
  ReplaySession session(replaying, replay_ex, o);
  // The replayer waits until its writer has matched a reader; best-effort samples reach the
  // reader only once the reader has matched the writer too, which under load comes later
  // (one CI run lost the first 14 of 30).
  ASSERT_TRUE(reader.WaitForMatched(1, 10.0));
  session.replayer().Start();
  ASSERT_TRUE(runtime::WaitFor(
      [&] {
        ex.SpinOnce(std::chrono::milliseconds(5));
        return session.replayer().done();
      },
      20.0));
  runtime::WaitFor([&] {
    ex.SpinOnce(std::chrono::milliseconds(5));
    return sequence.size() >= 30;
  }, 2.0);
  session.replayer().Stop();
  ASSERT_EQ(sequence.size(), 30u);
  for (int k = 0; k < 30; ++k) {
    EXPECT_EQ(sequence[k], static_cast<uint32_t>(k + 1));
    EXPECT_EQ(stamps[k], (k + 1) * 10'000'000LL);  // header stamps as recorded
  }
  const ReplayReport& r = session.replayer().report();
  EXPECT_EQ(r.sent.at("device/sonar/echo"), 30u);
  EXPECT_TRUE(r.finished);
  // 290 ms of recording at rate 2.
  EXPECT_GT(r.duration_s, 0.12);
  EXPECT_NE(session.Summary().find("open loop: 0 wheel commands ignored"), std::string::npos);
}

TEST(RecordingTest, ReplayTakesAStretchRemapsAndLoops) {
  const std::string file = TempPath("stretch.db3");
  WriteEchoes(file);
  runtime::Participant listener(
      ParticipantConfig{runtime::TestDomainId(), "listener", "", "", {}}, Catalog());
  runtime::Participant replaying(
      ParticipantConfig{runtime::TestDomainId(), "replay", "", "", {}}, Catalog());
  runtime::Executor ex, replay_ex;
  std::vector<uint32_t> sequence;
  // The echoes published on another topic (a catalogued one, for the test's reader).
  runtime::Reader<msgs::SonarEchoPubSubType> reader(
      listener, ex, "robot/sonar",
      [&](const msgs::SonarEcho& e) { sequence.push_back(e.header().sequence_number()); });
  ReplayOptions o;
  o.file = file;
  o.start_s = 0.1;      // from the sample at 110 ms (k = 11)
  o.duration_s = 0.1;   // to the one at 210 ms (k = 21)
  o.remap = {{"device/sonar/echo", "robot/sonar"}};
  o.topics = {"device/sonar/echo"};
  {
    ReplaySession session(replaying, replay_ex, o);
    session.replayer().Start();
    ASSERT_TRUE(runtime::WaitFor([&] {
      ex.SpinOnce(std::chrono::milliseconds(5));
      return session.replayer().done();
    }, 20.0));
    runtime::WaitFor([&] {
      ex.SpinOnce(std::chrono::milliseconds(5));
      return sequence.size() >= 11;
    }, 2.0);
    session.replayer().Stop();
    EXPECT_EQ(session.replayer().report().sent.at("robot/sonar"), 11u);
  }
  ASSERT_EQ(sequence.size(), 11u);
  EXPECT_EQ(sequence.front(), 11u);
  EXPECT_EQ(sequence.back(), 21u);

  // Looping: the stretch again and again until stopped.
  sequence.clear();
  o.loop = true;
  o.rate = 4.0;
  ReplaySession looping(replaying, replay_ex, o);
  looping.replayer().Start();
  EXPECT_TRUE(runtime::WaitFor([&] {
    ex.SpinOnce(std::chrono::milliseconds(5));
    return sequence.size() >= 33;
  }, 20.0));
  looping.replayer().Stop();
  EXPECT_GE(looping.replayer().report().passes, 3);
  EXPECT_FALSE(looping.replayer().report().finished);
  // Every pass starts where the first did. (The looping session's writer is new: its first
  // samples may go out before the reader has matched it, so the first pass may be cut.)
  int wraps = 0;
  for (std::size_t i = 0; i < sequence.size(); ++i) {
    EXPECT_GE(sequence[i], 11u) << "sample " << i;
    EXPECT_LE(sequence[i], 21u) << "sample " << i;
    if (i > 0 && sequence[i] < sequence[i - 1]) {
      ++wraps;
      EXPECT_EQ(sequence[i], 11u) << "pass " << wraps + 1 << " starts at sample " << i;
    }
  }
  EXPECT_GE(wraps, 2);

  // A remap of a topic the recording does not have, and a start past its end.
  ReplayOptions bad = o;
  bad.remap = {{"robot/nothing", "a/b"}};
  EXPECT_THROW(Replayer(replaying, bad), InputError);
  bad = o;
  bad.start_s = 5.0;
  EXPECT_THROW(Replayer(replaying, bad), InputError);
}

TEST(RecordingTest, BadReplayOptionsAreRefusedNamingTheOption) {
  const std::string file = TempPath("options.db3");
  {
    bag::BagWriter w(file);
    const auto id = w.AddTopic({0, "a/b", "stickrep::msgs::NotAType", "cdr", "[]"});
    const uint8_t bytes[8] = {0, 1, 0, 0, 1, 2, 3, 4};
    w.Write(id, 1, 1, bytes, sizeof(bytes));
  }
  runtime::Participant p(ParticipantConfig{runtime::TestDomainId(), "replay", "", "", {}},
                         Catalog());
  ReplayOptions o;
  o.file = file;
  o.rate = 40;
  EXPECT_THROW(ValidateReplayOptions(o), InputError);
  o.rate = 1;
  try {
    Replayer r(p, o);
    FAIL() << "a type this build does not know was replayed";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("NotAType"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ParseRemaps({"nocolon"}), InputError);
  EXPECT_EQ(ParseRemaps({"a/b:c/d"}).at("a/b"), "c/d");
  std::ostringstream check;
  EXPECT_EQ(CheckBag(file, check), 1) << check.str();
  EXPECT_NE(check.str().find("NotAType"), std::string::npos);
}

TEST(RecordingTest, APayloadThatDoesNotDeserializeIsNamedByCheck) {
  const std::string file = TempPath("bad_payload.db3");
  {
    bag::BagWriter w(file);
    const auto id = w.AddTopic({0, "device/camera/frame", "stickrep::msgs::Image", "cdr", "[]"});
    // A CDR header, then a header struct and a sequence length far beyond the payload.
    std::vector<uint8_t> bytes = {0, 1, 0, 0};
    for (int k = 0; k < 12; ++k) bytes.push_back(0);
    for (int k = 0; k < 8; ++k) bytes.push_back(0xff);
    w.Write(id, 5, 5, bytes.data(), bytes.size());
  }
  std::ostringstream check;
  EXPECT_EQ(CheckBag(file, check), 1) << check.str();
  EXPECT_NE(check.str().find("does not deserialize"), std::string::npos) << check.str();
}

TEST(RecordingTest, AFullDiskEndsTheRecordingAndKeepsWhatWasCommitted) {
  const std::string file = TempPath("full.db3");
  runtime::Participant p(ParticipantConfig{runtime::TestDomainId(), "publisher", "", "", {}},
                         Catalog());
  runtime::Writer<msgs::ImagePubSubType> frames(p, "device/camera/frame");
  RecordOptions o = Options(file, 10.0);
  o.topics = {"device/camera/frame"};
  o.max_bytes = 3'000'000;  // room for about 11 frames of 246 kB
  const RecordReport report = RecordWhile(o, [&] {
    ASSERT_TRUE(frames.WaitForMatched(1, 5.0));
    for (int k = 1; k <= 40; ++k) {
      msgs::Image img = Frame(k);
      frames.Publish(img, k);
      std::this_thread::sleep_for(std::chrono::milliseconds(60));
    }
  });
  EXPECT_FALSE(report.failure.empty());
  const auto stored = report.topics.at("device/camera/frame").stored;
  EXPECT_GT(stored, 0u);
  EXPECT_LT(stored, 40u);
  bag::BagReader reader(file);
  EXPECT_EQ(static_cast<uint64_t>(reader.Counts().begin()->second), stored);
  std::ostringstream check;
  EXPECT_EQ(CheckBag(file, check), 0) << check.str();
}

}  // namespace
}  // namespace stickrep::recording
