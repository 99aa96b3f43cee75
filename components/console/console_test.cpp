#include "console/console.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <iostream>
#include <sstream>
#include <thread>

#include <spdlog/spdlog.h>

#include "basePubSubTypes.h"
#include "common/input_error.h"
#include "console/message_json.h"
#include "console/doctor.h"
#include "console/message_types.h"
#include "console/topic_stats.h"
#include "runtime/raw_endpoint.h"
#include "runtime/endpoint.h"
#include "runtime/process.h"
#include "runtime/status_reporter.h"
#include "runtime/test_domain.h"

namespace stickrep::console {
namespace {

using ::testing::HasSubstr;

TEST(ConsoleTest, SummaryCountsWritersAndReadersAndTakesHistoryFromUserData) {
  std::vector<runtime::DiscoveredEndpoint> eps;
  eps.push_back({"robot/sonar", "stickrep::msgs::SonarScan", true, "best_effort", "volatile", 0, 0,
                 "stickrep;profile=sensor;history=keep_last 5;publish_mode=synchronous", "", ""});
  eps.push_back({"robot/sonar", "stickrep::msgs::SonarScan", false, "best_effort", "volatile", 0,
                 0, "stickrep;profile=sensor;history=keep_last 5", "", ""});
  eps.push_back({"robot/sonar", "stickrep::msgs::SonarScan", false, "best_effort", "volatile", 0,
                 0, "", "", ""});
  const auto topics = runtime::Summarise(eps);
  ASSERT_EQ(topics.size(), 1u);
  EXPECT_EQ(topics[0].writers, 1);
  EXPECT_EQ(topics[0].readers, 2);
  EXPECT_EQ(topics[0].history, "keep_last 5");
  EXPECT_EQ(topics[0].profile, "sensor");
}

TEST(ConsoleTest, TableShowsEveryColumn) {
  runtime::TopicSummary t;
  t.topic = "robot/motion/command";
  t.type = "stickrep::msgs::MotionCommand";
  t.writers = 1;
  t.readers = 1;
  t.reliability = "reliable";
  t.durability = "volatile";
  t.history = "keep_last 1";
  t.deadline_s = 0.5;
  std::ostringstream out;
  PrintTopicTable({t}, out);
  EXPECT_THAT(out.str(), HasSubstr("robot/motion/command"));
  EXPECT_THAT(out.str(), HasSubstr("reliable"));
  EXPECT_THAT(out.str(), HasSubstr("keep_last 1"));
  EXPECT_THAT(out.str(), HasSubstr("0.5 s"));
  EXPECT_THAT(out.str(), HasSubstr("1 topics"));
}

TEST(ConsoleTest, UserDataFieldReadsKeyValuePairs) {
  EXPECT_EQ(runtime::UserDataField("stickrep;profile=camera;history=keep_last 1", "history"),
            "keep_last 1");
  EXPECT_EQ(runtime::UserDataField("stickrep;profile=camera", "history"), "");
}

}  // namespace
}  // namespace stickrep::console

namespace stickrep::console {
namespace {

using ::testing::HasSubstr;

TEST(TopicWindowTest, RateAndPeriodSpreadFromReceptionTimes) {
  TopicWindow w(4);
  // Receptions 100 ms apart but one 200 ms gap; each 2 ms after its source time.
  const std::int64_t ms = 1'000'000;
  for (std::int64_t t : {0, 100, 200, 400, 500}) w.Add(t * ms, t * ms + 2 * ms, 10);
  EXPECT_EQ(w.total(), 5u);
  const Spread p = w.Period();  // the last 4 samples: periods 0.1, 0.2, 0.1
  EXPECT_EQ(p.n, 3u);
  EXPECT_NEAR(p.mean, 0.4 / 3, 1e-9);
  EXPECT_NEAR(p.min, 0.1, 1e-9);
  EXPECT_NEAR(p.max, 0.2, 1e-9);
  EXPECT_GT(p.stddev, 0.04);
  const Spread d = w.DelayMs();
  EXPECT_NEAR(d.mean, 2.0, 1e-9);
  EXPECT_NEAR(d.stddev, 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(w.MeanBytes(), 10.0);
}

TEST(TopicWindowTest, CloseNamesSuggestMistypedTopics) {
  const std::vector<std::string> known = {"robot/sonar", "robot/odometry", "device/sonar/echo",
                                          "localization/pose"};
  const auto close = CloseNames("robot/sonr", known);
  ASSERT_FALSE(close.empty());
  EXPECT_EQ(close.front(), "robot/sonar");
  EXPECT_TRUE(CloseNames("zzzzzzzzzzzzzzzzzzzzzz", known).empty());
}

// The verbs against a live writer on a domain of this test process's own.
class ConsoleLiveTest : public ::testing::Test {
 protected:
  ConsoleLiveTest()
      : publisher_(runtime::ParticipantConfig{runtime::TestDomainId(), "publisher", "", "", {}},
                   runtime::QosCatalog::LoadFile(runtime::DefaultConfigDir() + "/qos.yaml")),
        odometry_(publisher_, "robot/odometry") {
    options_.system_file = runtime::DefaultConfigDir() + "/system.yaml";
    options_.domain_id = runtime::TestDomainId();
    options_.timeout_s = 10.0;
    running_ = true;
    // 20 Hz until the test ends.
    thread_ = std::thread([this] {
      for (int k = 1; running_; ++k) {
        msgs::Odometry o;
        o.distance_in(k * 1.5);
        odometry_.Publish(o, k);
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      }
    });
  }
  ~ConsoleLiveTest() override {
    running_ = false;
    thread_.join();
  }

  runtime::Participant publisher_;
  runtime::Writer<msgs::OdometryPubSubType> odometry_;
  ConsoleOptions options_;
  std::atomic<bool> running_{false};
  std::thread thread_;
};

TEST_F(ConsoleLiveTest, HzMeasuresTheWritersRate) {
  options_.duration_s = 2.5;
  options_.json = true;
  std::ostringstream out;
  ASSERT_EQ(WatchTopic(options_, "robot/odometry", TopicStat::kRate, out), 0);
  std::istringstream lines(out.str());
  std::string line, last;
  while (std::getline(lines, line)) last = line;
  const auto j = nlohmann::json::parse(last);
  // 20 Hz written; the machine may stretch a period, never to half the rate on average.
  EXPECT_GT(j["rate_hz"].get<double>(), 12.0) << out.str();
  EXPECT_LT(j["rate_hz"].get<double>(), 22.0) << out.str();
  EXPECT_GT(j["period_max_s"].get<double>(), j["period_min_s"].get<double>());
}

TEST_F(ConsoleLiveTest, DelayIsSourceTimestampToReception) {
  options_.duration_s = 1.5;
  std::ostringstream out;
  ASSERT_EQ(WatchTopic(options_, "robot/odometry", TopicStat::kDelay, out), 0);
  EXPECT_THAT(out.str(), HasSubstr("robot/odometry: source timestamp to reception mean"));
}

TEST_F(ConsoleLiveTest, EchoOnceWithAField) {
  options_.count = 1;
  options_.field = "distance_in";
  std::ostringstream out;
  ASSERT_EQ(EchoTopic(options_, "robot/odometry", out), 0);
  const double d = std::stod(out.str());
  EXPECT_GT(d, 0.0);
  options_.field = "header.nope";
  EXPECT_THROW(EchoTopic(options_, "robot/odometry", out), InputError);
}

TEST_F(ConsoleLiveTest, AnUnknownTopicIsRefusedWithTheCloseNames) {
  try {
    WatchTopic(options_, "robot/odometri", TopicStat::kRate, std::cout);
    FAIL() << "an unknown topic was watched";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("did you mean: robot/odometry"));
  }
}

TEST_F(ConsoleLiveTest, InfoNamesEachEndpointsProcessHostAndQos) {
  // A heartbeat names the publisher's host, as every StickRep process's does.
  auto log = spdlog::default_logger();
  runtime::SampleCounters counters(log);
  runtime::StatusReporter heartbeat(publisher_, "publisher", "robot-a", counters);
  heartbeat.Publish(runtime::StatusReporter::State::kActive, "active; last warning: test");
  options_.wait_s = 1.5;
  options_.json = true;
  std::ostringstream out;
  ASSERT_EQ(InfoTopic(options_, "robot/odometry", false, out), 0);
  const auto j = nlohmann::json::parse(out.str());
  ASSERT_EQ(j["endpoints"].size(), 1u) << out.str();
  const auto& w = j["endpoints"][0];
  EXPECT_EQ(w["role"], "writer");
  EXPECT_EQ(w["process"], "publisher");
  EXPECT_EQ(w["host"], "robot-a");
  EXPECT_EQ(w["reliability"], "best_effort");
  EXPECT_EQ(w["history"], "keep_last 5");
  EXPECT_EQ(w["profile"], "sensor");

  std::ostringstream status;
  options_.json = false;
  options_.count = 1;
  ASSERT_EQ(ShowStatus(options_, status), 0);
  EXPECT_THAT(status.str(), HasSubstr("publisher"));
  EXPECT_THAT(status.str(), HasSubstr("robot-a"));
  EXPECT_THAT(status.str(), HasSubstr("ACTIVE"));
  EXPECT_THAT(status.str(), HasSubstr("last warning: test"));
}

TEST_F(ConsoleLiveTest, AOneShotStatusWaitsForAHeartbeatThatComesAfterItsFirstWindow) {
  // The first heartbeat comes 2.5 s after the status reader starts, after its first 1 s
  // window: a one-shot status still waits for it (up to the 10 s timeout) and prints it.
  auto log = spdlog::default_logger();
  runtime::SampleCounters counters(log);
  runtime::StatusReporter heartbeat(publisher_, "late", "robot-b", counters);
  std::thread later([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(2500));
    heartbeat.Publish(runtime::StatusReporter::State::kActive, "active");
  });
  options_.wait_s = 0.0;
  options_.count = 1;
  std::ostringstream status;
  const int code = ShowStatus(options_, status);
  later.join();
  EXPECT_EQ(code, 0);
  EXPECT_THAT(status.str(), HasSubstr("late"));
  EXPECT_THAT(status.str(), HasSubstr("robot-b"));
}

TEST_F(ConsoleLiveTest, DoctorNamesAReliableReaderOnABestEffortTopic) {
  // A reliable reader of robot/odometry, which is written best effort: they never match.
  runtime::Participant wrong(
      runtime::ParticipantConfig{runtime::TestDomainId(), "stickrep-wrong-reader", "", "", {}},
      runtime::QosCatalog::LoadFile(runtime::DefaultConfigDir() + "/qos.yaml"));
  runtime::Executor ex;
  runtime::QosProfile reliable;
  reliable.name = "wrong";
  reliable.reliability = runtime::QosProfile::Reliability::kReliable;
  runtime::RawReader reader(wrong, ex, "robot/odometry",
                            FindMessageType("stickrep::msgs::Odometry")->make_support, reliable,
                            [](const runtime::RawSample&, const runtime::RawSampleInfo&) {});
  options_.wait_s = 1.5;
  std::ostringstream out;
  EXPECT_EQ(Doctor(options_, out), 1);
  EXPECT_THAT(out.str(), HasSubstr("incompatible QoS"));
  EXPECT_THAT(out.str(), HasSubstr("robot/odometry"));
  EXPECT_THAT(out.str(), HasSubstr("policy reliability"));
  EXPECT_THAT(out.str(), HasSubstr("writer publisher offers best_effort"));
  EXPECT_THAT(out.str(), HasSubstr("reader stickrep-wrong-reader requests reliable"));
}

TEST(DoctorTest, EveryRuleNamesThePolicy) {
  runtime::DiscoveredEndpoint w{"a", "T", true, "best_effort", "volatile", 1.0, 2.0, "", "w1", "writer"};
  runtime::DiscoveredEndpoint r{"a", "T", false, "reliable", "transient_local", 0.5, 1.0, "", "r1",
                                "reader"};
  const auto f = Diagnose({w, r});
  std::vector<std::string> policies;
  for (const auto& x : f) policies.push_back(x.policy);
  EXPECT_THAT(policies, ::testing::UnorderedElementsAre("reliability", "durability", "deadline",
                                                        "liveliness lease"));
  runtime::DiscoveredEndpoint other = r;
  other.type = "U";
  EXPECT_EQ(Diagnose({w, other}).at(0).problem, "type mismatch");
  EXPECT_EQ(Diagnose({w}).at(0).problem, "no reader");
  EXPECT_EQ(Diagnose({r}).at(0).problem, "no writer");
  runtime::DiscoveredEndpoint fine = w;
  fine.is_writer = false;
  EXPECT_TRUE(Diagnose({w, fine}).empty());
}

TEST_F(ConsoleLiveTest, NoWriterWithinTheTimeoutIsExit1) {
  options_.timeout_s = 1.0;
  std::ostringstream out;
  EXPECT_EQ(WatchTopic(options_, "localization/pose", TopicStat::kRate, out), 1);
}

}  // namespace
}  // namespace stickrep::console
