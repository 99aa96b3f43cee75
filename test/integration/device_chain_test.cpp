// The virtual robot and the three device processes as separate processes: data flows from
// the simulated devices through sonar, camera and locomotion with the catalogued QoS, and
// locomotion stops the base when motion commands stop.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <set>

#include "basePubSubTypes.h"
#include "integration/process_fixture.h"
#include "runtime/process.h"
#include "sensorsPubSubTypes.h"
#include "systemPubSubTypes.h"

namespace stickrep::test {
namespace {

class DeviceChainTest : public ProcessFixture {
 protected:
  DeviceChainTest() : ProcessFixture(21) {}
};

const runtime::TopicSummary* Find(const std::vector<runtime::TopicSummary>& topics,
                                  const std::string& name) {
  for (const auto& t : topics) {
    if (t.topic == name) return &t;
  }
  return nullptr;
}

TEST_F(DeviceChainTest, SamplesFlowThroughTheDeviceProcessesWithTheCataloguedQos) {
  std::set<std::string> active;
  int scans_with_echoes = 0, good_images = 0;
  double odometer_in = 0.0, last_speed_ftps = -1.0;
  runtime::Reader<msgs::ComponentStatusPubSubType> status(
      participant(), executor(), "system/status", [&](const msgs::ComponentStatus& s) {
        if (s.state() == msgs::COMPONENT_ACTIVE) active.insert(s.component_name());
      });
  runtime::Reader<msgs::SonarScanPubSubType> sonar(
      participant(), executor(), "robot/sonar",
      [&](const msgs::SonarScan& s) { scans_with_echoes += s.valid_count() > 0; });
  runtime::Reader<msgs::ImagePubSubType> images(
      participant(), executor(), "robot/camera/image", [&](const msgs::Image& m) {
        good_images += m.width_px() == 512 && m.height_px() == 480 &&
                       m.data().size() == 512u * 480u;
      });
  runtime::Reader<msgs::OdometryPubSubType> odometry(
      participant(), executor(), "robot/odometry", [&](const msgs::Odometry& o) {
        odometer_in = o.distance_in();
        last_speed_ftps = o.linear_speed_ftps();
      });
  runtime::Writer<msgs::MotionCommandPubSubType> commands(participant(), "robot/motion/command");
  bool send_commands = true;
  executor().AddTimer(0.1, [&] {
    if (!send_commands) return;
    msgs::MotionCommand m;
    m.mode(msgs::MOTION_VELOCITY);
    m.linear_speed_ftps(1.0);
    commands.Publish(m, runtime::WallClockNowNs());
  });

  Start("stickrep-virtual-robot");
  Start("stickrep-sonar");
  Start("stickrep-camera");
  Start("stickrep-locomotion");

  ASSERT_TRUE(SpinUntil([&] { return active.size() == 4; }, 30.0)) << Outputs();
  ASSERT_TRUE(SpinUntil(
      [&] { return scans_with_echoes >= 5 && good_images >= 3 && odometer_in > 12.0; }, 30.0))
      << "scans " << scans_with_echoes << ", images " << good_images << ", odometer "
      << odometer_in << "\n"
      << Outputs();

  // The streams carry the QoS the catalogue gives them.
  ASSERT_TRUE(SpinUntil([&] { return Find(Topics(), "device/camera/frame") != nullptr; }, 10.0));
  const auto topics = Topics();
  const auto* scan_topic = Find(topics, "robot/sonar");
  ASSERT_NE(scan_topic, nullptr);
  EXPECT_EQ(scan_topic->reliability, "best_effort");
  EXPECT_EQ(scan_topic->history, "keep_last 5");
  const auto* frames = Find(topics, "device/camera/frame");
  EXPECT_EQ(frames->history, "keep_last 1");
  const auto* heartbeat = Find(topics, "system/status");
  EXPECT_EQ(heartbeat->durability, "transient_local");
  EXPECT_DOUBLE_EQ(heartbeat->liveliness_lease_s, 1.0);
  EXPECT_EQ(heartbeat->writers, 4);
  const auto* wheels = Find(topics, "device/base/wheel_command");
  EXPECT_EQ(wheels->reliability, "reliable");
  EXPECT_DOUBLE_EQ(wheels->deadline_s, 0.5);

  // Commands stop: locomotion must stop the base (command deadline / timeout).
  send_commands = false;
  const double at_stop = odometer_in;
  ASSERT_TRUE(SpinUntil([&] { return last_speed_ftps == 0.0; }, 10.0)) << Outputs();
  const double stopped_at = odometer_in;
  EXPECT_LT(stopped_at - at_stop, 12.0);  // under 1 s of travel at 1 ft/s

  StopAllAndExpectCleanExit();
}

}  // namespace
}  // namespace stickrep::test
