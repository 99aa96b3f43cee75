// The virtual robot's component on the in-process executor: the world moves by the wheel
// commands, the devices are served at their rates, and declared poses are judged.
#include "virtual_robot/virtual_robot_component.h"

#include <gtest/gtest.h>
#include <spdlog/sinks/null_sink.h>

#include <memory>
#include <vector>

#include "component/sim_executor.h"
#include "virtual_robot/test_world.h"

namespace stickrep::virtual_robot {
namespace {

class VirtualRobotComponentTest : public ::testing::Test {
 protected:
  void SetUp() override {
    config_.world = testing::Exact();
    config_.seed = 7;
    Make(/*start_in=*/100.0);
  }
  void Make(double start_in) {
    auto sim = std::make_unique<WorldSim>(map_, sensing::RobotConfig{}, config_.world, start_in,
                                          config_.seed);
    robot_ = std::make_unique<VirtualRobotComponent>(
        context_, config_, std::move(sim),
        VirtualRobotComponent::Outputs{executor_.Advertise<message::SonarEcho>("echo"),
                                       executor_.Advertise<message::Image>("frame"),
                                       executor_.Advertise<message::EncoderReading>("encoders"),
                                       executor_.Advertise<message::GroundTruth>("truth")});
    executor_.Subscribe<message::SonarEcho>("echo", [this](const auto&) { ++echoes_; });
    executor_.Subscribe<message::Image>("frame", [this](const auto&) { ++frames_; });
    executor_.Subscribe<message::GroundTruth>(
        "truth", [this](const message::GroundTruth& g) { truth_.push_back(g); });
    executor_.AddTimers(*robot_);
    robot_->Activate();
  }
  message::WheelCommand Wheels(double ftps) {
    message::WheelCommand w;
    w.header.stamp_ns = executor_.NowNs();
    w.left_speed_ftps = w.right_speed_ftps = ftps;
    return w;
  }
  message::LocalizationPose Localized(int edge, bool forward) {
    message::LocalizationPose p;
    p.status = message::LocalizationStatus::kLocalized;
    p.candidate_count = 1;
    p.best.ring_id = "square";
    p.best.edge_index = edge;
    p.best.forward = forward;
    p.edges_sensed = 4;
    return p;
  }

  map::Map map_ = testing::SquareRing();
  VirtualRobotConfig config_;
  component::SimExecutor executor_;
  std::shared_ptr<spdlog::logger> log_ = std::make_shared<spdlog::logger>(
      "test", std::make_shared<spdlog::sinks::null_sink_mt>());
  component::SampleCounters counters_{log_};
  component::Context context_{"virtual_robot", executor_, log_, counters_};
  std::unique_ptr<VirtualRobotComponent> robot_;
  int echoes_ = 0, frames_ = 0;
  std::vector<message::GroundTruth> truth_;
};

TEST_F(VirtualRobotComponentTest, DevicesAreServedAtTheirRatesOnItsClock) {
  executor_.RunUntil([] { return false; }, 2.0);
  EXPECT_EQ(echoes_, 20);   // 10 Hz
  EXPECT_EQ(frames_, 10);   // 5 Hz
  EXPECT_EQ(truth_.size(), 40u);  // with the encoders, 20 Hz
  EXPECT_EQ(robot_->frames(), 10);
}

TEST_F(VirtualRobotComponentTest, WheelCommandsMoveTheBaseUntilTheyStopComing) {
  // 2 ft/s for 1 s, refreshed every 0.1 s: 24 in.
  for (int i = 0; i < 10; ++i) {
    robot_->OnWheels(Wheels(2.0));
    executor_.RunUntil([] { return false; }, executor_.ElapsedS() + 0.1);
  }
  const double moved = robot_->sim().Truth().distance_in;
  EXPECT_NEAR(moved, 24.0, 1.0);
  // No command for longer than wheel_command_timeout_s: the base stops by itself.
  executor_.RunUntil([] { return false; }, executor_.ElapsedS() + 2.0);
  EXPECT_LT(robot_->sim().Truth().distance_in - moved, 0.5 * 12.0 * 2.0 + 1.0);
  const double stopped_at = robot_->sim().Truth().distance_in;
  executor_.RunUntil([] { return false; }, executor_.ElapsedS() + 1.0);
  EXPECT_DOUBLE_EQ(robot_->sim().Truth().distance_in, stopped_at);
}

TEST_F(VirtualRobotComponentTest, EachRecoveryIsJudgedOnceAgainstTheTruth) {
  executor_.RunUntil([] { return false; }, 0.2);
  const SimTruth t = robot_->sim().Truth();
  robot_->OnPose(Localized(t.seen_edge_index, t.seen_forward_in_ring));
  robot_->OnPose(Localized(t.seen_edge_index, t.seen_forward_in_ring));  // the same recovery
  ASSERT_EQ(robot_->checks().size(), 1u);
  EXPECT_TRUE(robot_->checks()[0].correct);
  EXPECT_EQ(robot_->checks()[0].edges_sensed, 4);
  // Lost, then a wrong pose: a second recovery, judged incorrect.
  message::LocalizationPose lost;
  lost.status = message::LocalizationStatus::kLost;
  robot_->OnPose(lost);
  robot_->OnPose(Localized((t.seen_edge_index + 3) % 6, t.seen_forward_in_ring));
  ASSERT_EQ(robot_->checks().size(), 2u);
  EXPECT_FALSE(robot_->checks()[1].correct);
  EXPECT_NE(robot_->Summary().find("INCORRECT"), std::string::npos);
}

// A robot configured to be kidnapped, made once: the executor keeps a robot's timers, so a
// robot must not be replaced on it.
class VirtualRobotKidnapTest : public VirtualRobotComponentTest {
 protected:
  void SetUp() override {
    config_.world = testing::Exact();
    config_.seed = 7;
    config_.kidnap_after_localized_s = 1.0;
    config_.kidnap_jump_in = 400.0;
    Make(/*start_in=*/100.0);
  }
};

TEST_F(VirtualRobotKidnapTest, TheRobotIsKidnappedTheConfiguredTimeAfterTheFirstPose) {
  const SimTruth t = robot_->sim().Truth();
  robot_->OnPose(Localized(t.seen_edge_index, t.seen_forward_in_ring));
  executor_.RunUntil([] { return false; }, 0.9);
  EXPECT_FALSE(robot_->kidnapped());
  executor_.RunUntil([this] { return robot_->kidnapped(); }, 1.2);
  EXPECT_TRUE(robot_->kidnapped());
  EXPECT_NE(robot_->sim().Truth().edge_index, t.edge_index);
  EXPECT_DOUBLE_EQ(robot_->TravelledSinceEpochFt(), 0.0);
}

}  // namespace
}  // namespace stickrep::virtual_robot
