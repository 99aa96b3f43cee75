// The locomotion component on its own, on a clock the test sets: commands drive the base,
// silence stops it, and a non-finite speed stops it at once.
#include "locomotion/locomotion_component.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <spdlog/sinks/null_sink.h>

#include <cmath>
#include <vector>

#include "locomotion/fake_sonar.h"

namespace stickrep::locomotion {
namespace {

template <typename T>
class RecordingPublisher : public component::Publisher<T> {
 public:
  bool Publish(const T& s) override {
    sent.push_back(s);
    return true;
  }
  std::vector<T> sent;
};

class ManualClock : public component::Clock {
 public:
  int64_t NowNs() const override { return now_ns; }
  int64_t now_ns = 1'000'000'000;
};

class LocomotionComponentTest : public ::testing::Test {
 protected:
  LocomotionComponentTest()
      : log_(std::make_shared<spdlog::logger>("t", std::make_shared<spdlog::sinks::null_sink_mt>())),
        counters_(log_),
        ctx_{"locomotion", clock_, log_, counters_},
        base_(ctx_, LocomotionConfig{}, 15.0, {wheels_, odometry_, state_}) {}

  message::MotionCommand Velocity(double ftps) const {
    message::MotionCommand m;
    m.mode = message::MotionMode::kVelocity;
    m.linear_speed_ftps = ftps;
    return m;
  }

  ManualClock clock_;
  std::shared_ptr<spdlog::logger> log_;
  component::SampleCounters counters_;
  component::Context ctx_;
  RecordingPublisher<message::WheelCommand> wheels_;
  RecordingPublisher<message::Odometry> odometry_;
  RecordingPublisher<message::MotionState> state_;
  LocomotionComponent base_;
};

TEST_F(LocomotionComponentTest, ACommandDrivesTheWheelsUntilCommandsStop) {
  base_.OnCommand(Velocity(1.0));
  base_.Watchdog();
  ASSERT_FALSE(wheels_.sent.empty());
  EXPECT_GT(wheels_.sent.back().left_speed_ftps, 0.5);
  clock_.now_ns += 400'000'000;  // within the 0.5 s command timeout
  base_.Watchdog();
  EXPECT_GT(wheels_.sent.back().left_speed_ftps, 0.5);
  clock_.now_ns += 200'000'000;  // 0.6 s without a command
  base_.Watchdog();
  EXPECT_EQ(wheels_.sent.back().left_speed_ftps, 0.0);
  EXPECT_EQ(state_.sent.back().state, message::LocomotionState::kStopped);
  EXPECT_NE(state_.sent.back().message.find("no motion command"), std::string::npos)
      << state_.sent.back().message;
}

TEST_F(LocomotionComponentTest, ANonFiniteSpeedStopsTheBaseAndIsCounted) {
  base_.OnCommand(Velocity(1.0));
  base_.OnCommand(Velocity(std::nan("")));
  base_.Watchdog();
  EXPECT_EQ(wheels_.sent.back().left_speed_ftps, 0.0);
  EXPECT_EQ(counters_.dropped(), 1u);
}

TEST_F(LocomotionComponentTest, EncodersBecomeOdometryStampedOnTheBaseClock) {
  message::EncoderReading e;
  e.header.stamp_ns = 5'000'000'000;
  base_.OnEncoders(e);
  e.header.stamp_ns = 5'050'000'000;
  e.left_travel_in = e.right_travel_in = 2.0;
  base_.OnEncoders(e);
  ASSERT_EQ(odometry_.sent.size(), 2u);
  EXPECT_EQ(odometry_.sent[1].header.stamp_ns, 5'050'000'000);
  EXPECT_DOUBLE_EQ(odometry_.sent[1].distance_in, 2.0);
  e.header.stamp_ns = 4'000'000'000;
  base_.OnEncoders(e);
  EXPECT_EQ(counters_.dropped(), 1u);  // time went backwards
}

TEST_F(LocomotionComponentTest, FollowingWithWheelsThatDoNotTurnIsAStallCountedAndSaid) {
  // A 120 in hallway seen from its axis, and encoders that never move: the base is held by
  // something the sonar does not see.
  message::SonarScan scan;
  const std::vector<SonarRange> ranges = fake::Scan(fake::Hallway(60), 0.0, 0.0, 0.0);
  for (size_t k = 0; k < ranges.size() && k < scan.range_in.size(); ++k) {
    scan.range_in[k] = static_cast<float>(ranges[k].range_in);
    scan.state[k] = ranges[k].valid ? sonar::ReadingState::kValid : sonar::ReadingState::kNoEcho;
  }
  message::MotionCommand follow;
  follow.mode = message::MotionMode::kFollowHallway;
  follow.linear_speed_ftps = 1.0;
  message::EncoderReading still;
  bool said = false;
  for (int step = 0; step < 40 && !said; ++step) {  // up to 2 s at 20 Hz
    clock_.now_ns += 50'000'000;
    base_.OnCommand(follow);
    scan.header.stamp_ns = still.header.stamp_ns = clock_.now_ns;
    base_.OnScan(scan);
    base_.OnEncoders(still);
    said = state_.sent.back().message.find("stalled") != std::string::npos;
  }
  ASSERT_TRUE(said) << state_.sent.back().message;
  EXPECT_THAT(state_.sent.back().message, ::testing::HasSubstr("travel reversed, now backward"));
  EXPECT_THAT(base_.Summary(), ::testing::HasSubstr("1 reversals, 0 obstacle stops, 1 stalls"));
  EXPECT_EQ(wheels_.sent.back().left_speed_ftps, 0.0);
}

}  // namespace
}  // namespace stickrep::locomotion
