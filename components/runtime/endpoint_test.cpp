#include "runtime/endpoint.h"

#include <gtest/gtest.h>

#include <cstring>

#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>

#include "basePubSubTypes.h"
#include "perceptionPubSubTypes.h"
#include "runtime/guarded_type.h"
#include "runtime/raw_endpoint.h"
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

using Bytes = std::vector<std::uint8_t>;

Bytes Serialize(msgs::LandmarkObservation m) {
  msgs::LandmarkObservationPubSubType support;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(support.getSerializedSizeProvider(&m)());
  EXPECT_TRUE(support.serialize(&m, &payload));
  return Bytes(payload.data, payload.data + payload.length);
}

// Payloads Fast CDR cannot read, as the fuzz targets found them: a boolean byte of 2
// (fuzz_perception_cdr) and an encapsulation header that is not CDR (fuzz_sensors_cdr). The
// generated deserialize lets Fast CDR's BadParamException escape for both.
std::vector<Bytes> MalformedObservations(double width_in) {
  msgs::LandmarkObservation m;
  m.width_in(width_in);
  m.in_envelope(false);
  const Bytes no = Serialize(m);
  m.in_envelope(true);
  const Bytes yes = Serialize(m);
  Bytes bad_bool = no;
  for (std::size_t i = 0; i < no.size(); ++i) {
    if (no[i] != yes[i]) bad_bool[i] = 2;
  }
  Bytes bad_header = no;
  bad_header[0] = 0x7f;
  return {bad_bool, bad_header};
}

TEST(GuardedPubSubTypeTest, RefusesMalformedPayloadsInsteadOfThrowing) {
  runtime::GuardedPubSubType<msgs::LandmarkObservationPubSubType> support;
  for (Bytes bytes : MalformedObservations(30.0)) {
    eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<uint32_t>(bytes.size()));
    std::memcpy(payload.data, bytes.data(), bytes.size());
    payload.length = static_cast<uint32_t>(bytes.size());
    msgs::LandmarkObservation m;
    bool ok = true;
    EXPECT_NO_THROW(ok = support.deserialize(&payload, &m));
    EXPECT_FALSE(ok);
  }
  msgs::LandmarkObservation good;
  good.width_in(36.0);
  Bytes bytes = Serialize(good);
  eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<uint32_t>(bytes.size()));
  std::memcpy(payload.data, bytes.data(), bytes.size());
  payload.length = static_cast<uint32_t>(bytes.size());
  msgs::LandmarkObservation m;
  EXPECT_TRUE(support.deserialize(&payload, &m));
  EXPECT_DOUBLE_EQ(m.width_in(), 36.0);
}

// A malformed sample from the network is dropped and the reader takes the next one; the
// exception used to leave Drain on the executor thread and end the process.
TEST_F(EndpointTest, MalformedPayloadIsDroppedAndTheNextSampleArrives) {
  Executor ex;
  std::vector<msgs::LandmarkObservation> got;
  Reader<msgs::LandmarkObservationPubSubType> reader(
      b_, ex, "perception/landmark",
      [&](const msgs::LandmarkObservation& m) { got.push_back(m); });
  RawWriter writer(a_, "perception/landmark",
                   [] { return new msgs::LandmarkObservationPubSubType(); },
                   catalog_.ForTopic("perception/landmark"));
  ASSERT_TRUE(reader.WaitForMatched(1, 10.0));
  ASSERT_TRUE(WaitFor([&] { return writer.matched() >= 1; }, 10.0));
  for (const Bytes& bad : MalformedObservations(30.0)) {
    ASSERT_TRUE(writer.Publish(bad.data(), bad.size()));
  }
  msgs::LandmarkObservation good;
  good.width_in(33.0);
  const Bytes bytes = Serialize(good);
  ASSERT_TRUE(writer.Publish(bytes.data(), bytes.size()));
  ASSERT_TRUE(SpinUntil(ex, [&] { return !got.empty(); }, 10.0));
  SpinUntil(ex, [] { return false; }, 0.3);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_DOUBLE_EQ(got[0].width_in(), 33.0);
}

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
