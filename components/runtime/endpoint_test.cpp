#include "runtime/endpoint.h"

#include <gtest/gtest.h>

#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>

#include "basePubSubTypes.h"
#include "perceptionPubSubTypes.h"
#include "runtime/system_config.h"
#include "runtime/test_domain.h"
#include "systemPubSubTypes.h"

namespace stickrep::runtime {
namespace {

class EndpointTest : public ::testing::Test {
 protected:
  EndpointTest()
      : catalog_(QosCatalog::LoadFile(DefaultConfigDir() + "/qos.yaml")),
        a_(ParticipantConfig{TestDomainId(), "test-a", "", "", {}}, catalog_),
        b_(ParticipantConfig{TestDomainId(), "test-b", "", "", {}}, catalog_) {}

  // Spins the executor until `done` or the timeout; the condition is what passes the test.
  bool SpinUntil(Executor& ex, const std::function<bool()>& done, double timeout_s) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration_cast<
        std::chrono::steady_clock::duration>(std::chrono::duration<double>(timeout_s));
    while (!done()) {
      if (std::chrono::steady_clock::now() > until) return false;
      ex.SpinOnce(std::chrono::milliseconds(20));
    }
    return true;
  }

  QosCatalog catalog_;
  Participant a_;
  Participant b_;
};

TEST_F(EndpointTest, SamplesFlowWithHeaderStampedAndSequenced) {
  Executor ex;
  // perception/landmark keeps 50 samples, so a burst of three must arrive whole.
  std::vector<msgs::LandmarkObservation> got;
  Reader<msgs::LandmarkObservationPubSubType> reader(
      b_, ex, "perception/landmark",
      [&](const msgs::LandmarkObservation& m) { got.push_back(m); });
  Writer<msgs::LandmarkObservationPubSubType> writer(a_, "perception/landmark");
  ASSERT_TRUE(writer.WaitForMatched(1, 10.0));
  ASSERT_TRUE(reader.WaitForMatched(1, 10.0));
  for (int i = 0; i < 3; ++i) {
    msgs::LandmarkObservation m;
    m.width_in(30.0 + i);
    ASSERT_TRUE(writer.Publish(m, 1000 + i));
  }
  ASSERT_TRUE(SpinUntil(ex, [&] { return got.size() == 3; }, 10.0));
  EXPECT_EQ(got[0].header().sequence_number(), 1u);
  EXPECT_EQ(got[2].header().sequence_number(), 3u);
  EXPECT_EQ(got[2].header().stamp_ns(), 1002);
  EXPECT_DOUBLE_EQ(got[2].width_in(), 32.0);
}

TEST_F(EndpointTest, ReaderGetsTheCataloguedQos) {
  Executor ex;
  Reader<msgs::ComponentStatusPubSubType> reader(b_, ex, "system/status",
                                                [](const msgs::ComponentStatus&) {});
  Writer<msgs::ComponentStatusPubSubType> writer(a_, "system/status");
  ASSERT_TRUE(reader.WaitForMatched(1, 10.0));
  // Reaching a match at all proves compatibility; check the kinds the catalogue asked for.
  const QosProfile& p = catalog_.ForTopic("system/status");
  EXPECT_EQ(p.reliability, QosProfile::Reliability::kReliable);
  const auto q = ToDataReaderQos(p, eprosima::fastdds::dds::DataReaderQos());
  EXPECT_EQ(q.durability().kind, eprosima::fastdds::dds::TRANSIENT_LOCAL_DURABILITY_QOS);
  EXPECT_EQ(q.history().depth, 1);
  EXPECT_EQ(q.liveliness().lease_duration.seconds, 1);
}

TEST_F(EndpointTest, LateJoiningReaderOfLatchedTopicGetsTheLastSample) {
  Writer<msgs::ComponentStatusPubSubType> writer(a_, "system/status");
  msgs::ComponentStatus s;
  s.component_name("sonar");
  s.state(msgs::COMPONENT_ACTIVE);
  writer.Publish(s, 1);
  Executor ex;
  std::vector<std::string> got;
  Reader<msgs::ComponentStatusPubSubType> reader(
      b_, ex, "system/status",
      [&](const msgs::ComponentStatus& m) { got.push_back(m.component_name()); });
  ASSERT_TRUE(SpinUntil(ex, [&] { return !got.empty(); }, 10.0));
  EXPECT_EQ(got.front(), "sonar");
}

TEST_F(EndpointTest, DeadlineMissIsReportedWhenCommandsStop) {
  Executor ex;
  int misses = 0;
  Reader<msgs::MotionCommandPubSubType> reader(b_, ex, "robot/motion/command",
                                              [](const msgs::MotionCommand&) {});
  reader.OnDeadlineMissed([&] { misses++; });
  Writer<msgs::MotionCommandPubSubType> writer(a_, "robot/motion/command");
  // Both sides matched: a writer that has not matched the reader yet sends it nothing, and a
  // reader's deadline starts with its first sample.
  ASSERT_TRUE(reader.WaitForMatched(1, 10.0));
  ASSERT_TRUE(writer.WaitForMatched(1, 10.0));
  msgs::MotionCommand m;
  writer.Publish(m, 1);
  // The catalogue's deadline is 0.5 s: with no further command a miss must be reported.
  ASSERT_TRUE(SpinUntil(ex, [&] { return misses > 0; }, 5.0));
}

TEST_F(EndpointTest, LivelinessDropsWhenTheWriterGoesAway) {
  Executor ex;
  std::vector<int> alive_history;
  Reader<msgs::ComponentStatusPubSubType> reader(b_, ex, "system/status",
                                                [](const msgs::ComponentStatus&) {});
  reader.OnLivelinessChanged([&](int alive) { alive_history.push_back(alive); });
  {
    Writer<msgs::ComponentStatusPubSubType> writer(a_, "system/status");
    msgs::ComponentStatus s;
    s.component_name("camera");
    writer.Publish(s, 1);
    ASSERT_TRUE(SpinUntil(ex, [&] { return !alive_history.empty() && alive_history.back() == 1; },
                          10.0));
  }
  ASSERT_TRUE(SpinUntil(ex, [&] { return alive_history.back() == 0; }, 10.0));
}

}  // namespace
}  // namespace stickrep::runtime
