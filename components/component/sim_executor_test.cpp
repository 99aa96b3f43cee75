#include "component/sim_executor.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <fmt/format.h>

#include "messages/messages.h"

namespace stickrep::component {
namespace {

TEST(SimExecutorTest, TimersFireInTimeOrderAndTiesInTheOrderAdded) {
  SimExecutor e;
  std::vector<std::string> fired;
  e.AddTimer(0.5, [&] { fired.push_back(fmt::format("a{:.1f}", e.ElapsedS())); });
  e.AddTimer(0.2, [&] { fired.push_back(fmt::format("b{:.1f}", e.ElapsedS())); });
  e.RunUntil([] { return false; }, 1.0);
  EXPECT_EQ(fired, (std::vector<std::string>{"b0.2", "b0.4", "a0.5", "b0.6", "b0.8", "a1.0",
                                             "b1.0"}));
}

TEST(SimExecutorTest, SamplesReachSubscribersInOrderBeforeTheClockMovesOn) {
  SimExecutor e;
  Publisher<message::Odometry>& out = e.Advertise<message::Odometry>("robot/odometry");
  std::vector<std::pair<uint32_t, double>> got;
  int64_t delivered_at = 0;
  e.Subscribe<message::Odometry>("robot/odometry", [&](const message::Odometry& o) {
    got.push_back({o.header.sequence, o.distance_in});
    delivered_at = e.NowNs();
  });
  int64_t published_at = 0;
  e.AddTimer(0.1, [&] {
    published_at = e.NowNs();
    message::Odometry o;
    o.distance_in = 12.0 * static_cast<double>(got.size() + 1);
    out.Publish(o);
    out.Publish(o);
  });
  e.RunUntil([&] { return got.size() >= 4; }, 10.0);
  ASSERT_EQ(got.size(), 4u);
  EXPECT_EQ(got[0].first, 1u);
  EXPECT_EQ(got[3].first, 4u);
  EXPECT_DOUBLE_EQ(got[2].second, 36.0);  // the second round saw the first round's samples
  EXPECT_EQ(delivered_at, published_at);
}

TEST(SimExecutorTest, ASampleChainIsDeliveredWithinOneStep) {
  SimExecutor e;
  auto& scans = e.Advertise<message::SonarScan>("robot/sonar");
  auto& poses = e.Advertise<message::LocalizationPose>("localization/pose");
  int poses_seen = 0;
  e.Subscribe<message::SonarScan>("robot/sonar",
                                  [&](const message::SonarScan&) { poses.Publish({}); });
  e.Subscribe<message::LocalizationPose>("localization/pose",
                                         [&](const message::LocalizationPose&) { ++poses_seen; });
  e.AddTimer(1.0, [&] { scans.Publish({}); });
  e.Step();
  EXPECT_EQ(poses_seen, 1);
  EXPECT_EQ(e.delivered(), 2u);
}

TEST(SimExecutorTest, OneTopicCannotCarryTwoTypes) {
  SimExecutor e;
  e.Advertise<message::Odometry>("robot/odometry");
  EXPECT_THROW(e.Advertise<message::SonarScan>("robot/odometry"), std::logic_error);
}

TEST(SimExecutorTest, RunUntilStopsAtTheBound) {
  SimExecutor e;
  int ticks = 0;
  e.AddTimer(0.25, [&] { ++ticks; });
  EXPECT_FALSE(e.RunUntil([] { return false; }, 2.0));
  EXPECT_EQ(ticks, 8);
  EXPECT_DOUBLE_EQ(e.ElapsedS(), 2.0);
  EXPECT_TRUE(e.RunUntil([&] { return ticks == 10; }, 5.0));
}

}  // namespace
}  // namespace stickrep::component
