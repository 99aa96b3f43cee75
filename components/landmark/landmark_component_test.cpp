// The landmark component on its own: a frame is paired with the scan and the odometer of its
// own instant, waits for them, and is dropped with a reason when they cannot come.
#include "landmark/landmark_component.h"

#include <gtest/gtest.h>
#include <spdlog/sinks/null_sink.h>

#include <vector>

namespace stickrep::landmark {
namespace {

class RecordingPublisher : public component::Publisher<message::LandmarkObservation> {
 public:
  bool Publish(const message::LandmarkObservation& o) override {
    sent.push_back(o);
    return true;
  }
  std::vector<message::LandmarkObservation> sent;
};

class FixedClock : public component::Clock {
 public:
  int64_t NowNs() const override { return 1; }
};

constexpr int64_t kS = 1'000'000'000;

class LandmarkComponentTest : public ::testing::Test {
 protected:
  LandmarkComponentTest()
      : log_(std::make_shared<spdlog::logger>("t", std::make_shared<spdlog::sinks::null_sink_mt>())),
        counters_(log_),
        ctx_{"landmark", clock_, log_, counters_},
        robot_(),
        landmark_(ctx_, robot_, LandmarkConfig{}, out_) {}

  message::SonarScan Scan(int64_t stamp) const {
    message::SonarScan s;
    s.header.stamp_ns = stamp;
    s.state.fill(sonar::ReadingState::kNoEcho);
    s.state[robot_.camera.coaxial_sensor] = sonar::ReadingState::kValid;
    s.range_in[robot_.camera.coaxial_sensor] = 60.0f;
    return s;
  }
  message::Odometry Odometry(int64_t stamp, double distance_in) const {
    message::Odometry o;
    o.header.stamp_ns = stamp;
    o.distance_in = distance_in;
    return o;
  }
  message::Image Frame(int64_t stamp, uint32_t sequence) const {
    message::Image m;
    m.header = {stamp, sequence};
    m.width_px = static_cast<uint32_t>(robot_.camera.image_width_px);
    m.height_px = static_cast<uint32_t>(robot_.camera.image_height_px);
    m.step_bytes = m.width_px;
    m.encoding = "mono8";
    m.data.assign(static_cast<size_t>(m.width_px) * m.height_px, 128);
    return m;
  }

  FixedClock clock_;
  std::shared_ptr<spdlog::logger> log_;
  component::SampleCounters counters_;
  component::Context ctx_;
  sensing::RobotConfig robot_;
  RecordingPublisher out_;
  LandmarkComponent landmark_;
};

TEST_F(LandmarkComponentTest, AFrameWaitsForTheOdometryOfItsOwnInstant) {
  landmark_.OnOdometry(Odometry(10 * kS, 100.0));
  landmark_.OnScan(Scan(10 * kS + kS / 10));
  landmark_.OnImage(Frame(10 * kS + kS / 10, 1));
  EXPECT_EQ(landmark_.frames_processed(), 0u);  // the odometry of 10.1 s has not come yet
  landmark_.OnOdometry(Odometry(10 * kS + kS / 5, 110.0));
  EXPECT_EQ(landmark_.frames_processed(), 1u);
  EXPECT_EQ(counters_.dropped(), 0u);
}

TEST_F(LandmarkComponentTest, AFrameWithNoScanNearItIsDroppedWithTheReason) {
  landmark_.OnOdometry(Odometry(10 * kS, 100.0));
  landmark_.OnImage(Frame(10 * kS, 1));
  // Scans and odometry a second later: the frame's own scan can no longer come.
  landmark_.OnScan(Scan(11 * kS));
  landmark_.OnOdometry(Odometry(11 * kS, 110.0));
  EXPECT_EQ(landmark_.frames_processed(), 0u);
  ASSERT_EQ(counters_.dropped(), 1u);
  EXPECT_EQ(counters_.dropped_by_reason().begin()->first,
            "robot/camera/image: no sonar scan near the frame in time");
}

TEST_F(LandmarkComponentTest, OdometryGoingBackInTimeIsDropped) {
  landmark_.OnOdometry(Odometry(10 * kS, 100.0));
  landmark_.OnOdometry(Odometry(9 * kS, 90.0));
  EXPECT_EQ(counters_.dropped_by_reason().begin()->first, "robot/odometry: time went backwards");
}

}  // namespace
}  // namespace stickrep::landmark
