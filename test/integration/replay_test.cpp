// The acceptance experiment of recorded data: an all-in-one run on the small map is recorded
// (the device streams and sim/ground_truth); the recording is replayed into sonar, camera,
// locomotion, landmark, localizer and executive, with no virtual robot, at rate 1 and 4.
// The localizer must recover the pose of the live run, and replays of one recording must
// sense the same edge sequence.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <iterator>
#include <optional>
#include <regex>
#include <sstream>
#include <vector>

#include "integration/process_fixture.h"
#include "localizationPubSubTypes.h"
#include "missionPubSubTypes.h"
#include "runtime/process.h"
#include "systemPubSubTypes.h"

namespace stickrep::test {
namespace {

constexpr const char* kRecordedTopics =
    "device/sonar/echo,device/camera/frame,device/base/encoders,sim/ground_truth";
// What the pipeline reads: the replay starts once each has a matched reader (nothing in the
// pipeline reads sim/ground_truth, so replaying it would make the replay wait its whole
// --wait and then start into whatever had matched by then).
constexpr const char* kReplayedTopics =
    "device/sonar/echo,device/camera/frame,device/base/encoders";

struct Pose {
  std::string ring;
  int edge = -1;
  bool forward = false;
  bool operator==(const Pose& o) const {
    return ring == o.ring && edge == o.edge && forward == o.forward;
  }
};

std::ostream& operator<<(std::ostream& out, const Pose& p) {
  return out << "ring '" << p.ring << "' edge " << p.edge << (p.forward ? " forward" : " backward");
}

// Two sensed sequences ("wall:129 door36 wall:102 ...") agree: every edge is of the same
// kind in the same order; every complete edge is within `edge_tol_in`, and the partial first
// edge, which runs from the localizer's first odometry sample, within `first_edge_tol_in`.
// Where that first sample falls depends on when locomotion's odometry writer matched the
// localizer's reader: discovery between two processes the test does not see (one CI run lost
// 8 in of a 129 in first wall at rate 1). A complete edge moves when the frames that place a
// door differ: at rate 4 a frame can be superseded in the keep-last-1 image stream while the
// landmark process is busy (one CI run measured a wall of 177 in where the replay before it
// measured 176 in).
::testing::AssertionResult SensedAlike(const std::string& a, const std::string& b,
                                       double first_edge_tol_in, double edge_tol_in) {
  std::istringstream sa(a), sb(b);
  std::vector<std::string> ta{std::istream_iterator<std::string>(sa), {}};
  std::vector<std::string> tb{std::istream_iterator<std::string>(sb), {}};
  const auto fail = [&] {
    return ::testing::AssertionFailure() << "\"" << a << "\" vs \"" << b << "\"";
  };
  if (ta.empty() || ta.size() != tb.size()) return fail();
  const auto split = [](const std::string& t) {
    const auto colon = t.find(':');
    return colon == std::string::npos
               ? std::make_pair(t, 0.0)
               : std::make_pair(t.substr(0, colon), std::stod(t.substr(colon + 1)));
  };
  for (size_t k = 0; k < ta.size(); ++k) {
    const auto [kind_a, len_a] = split(ta[k]);
    const auto [kind_b, len_b] = split(tb[k]);
    const double tol = k == 0 ? first_edge_tol_in : edge_tol_in;
    if (kind_a != kind_b || std::abs(len_a - len_b) > tol) return fail();
  }
  return ::testing::AssertionSuccess();
}

class ReplayTest : public ProcessFixture {
 protected:
  ReplayTest() : ProcessFixture(45) {}

  void SetUp() override {
    system_ = SmallMapSystem("replay_system.yaml");
    const auto dir = std::filesystem::path(system_).parent_path();
    recording_ = (dir / "replay_test_run.db3").string();
    for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(recording_ + suffix);
    poses_ = std::make_unique<runtime::Reader<msgs::LocalizationPosePubSubType>>(
        participant(), executor(), "localization/pose", [this](const msgs::LocalizationPose& p) {
          if (p.status() == msgs::LOCALIZATION_LOCALIZED && !pose_) {
            pose_ = Pose{p.best().ring_id(), static_cast<int>(p.best().edge_index()),
                         p.best().forward()};
          }
        });
    mission_ = std::make_unique<runtime::Reader<msgs::MissionStatusPubSubType>>(
        participant(), executor(), "mission/status",
        [this](const msgs::MissionStatus& s) { state_ = s.state(); });
  }

  // Every process but the virtual robot; the executive ends once the pose is recovered.
  std::map<std::string, launch::ChildProcess*> StartPipeline() {
    std::map<std::string, launch::ChildProcess*> started;
    for (const char* exe : {"stickrep-sonar", "stickrep-camera", "stickrep-locomotion",
                            "stickrep-landmark", "stickrep-localizer"}) {
      started[exe] = &Start(exe, {"--system", system_});
    }
    started["stickrep-executive"] =
        &Start("stickrep-executive",
               {"--system", system_, "--config",
                WriteTempFile("replay_exec.yaml",
                              ConfigWith("executive.yaml", {{"exit_when_localized", "true"}}))});
    return started;
  }

  // The sequence the localizer logged when it declared the pose. The log line follows the
  // published pose, so it may arrive a moment after the pose does: waited for, bounded.
  std::string SensedSequence(launch::ChildProcess& localizer) {
    static const std::regex sensed("info sensed: ([^\n]*)\n");
    std::smatch m;
    SpinUntil(
        [&] {
          localizer.ReadLines(false);
          return std::regex_search(localizer.output(), m, sensed);
        },
        10.0);
    localizer.ReadLines(true);
    const std::string out = localizer.output();
    return std::regex_search(out, m, sensed) ? m[1].str() : "";
  }

  // A live run recorded: the pose it recovered and the sequence it sensed.
  std::pair<Pose, std::string> RecordLiveRun() {
    Start("stickrep-virtual-robot",
          {"--system", system_, "--config",
           WriteTempFile(
               "replay_vr.yaml",
               ConfigWith("virtual_robot.yaml",
                          {{"real_time_factor", "2"}, {"seed", "2"}, {"summary_png", "\"\""}}))});
    launch::ChildProcess& recorder = Start(
        "stickrep-record", {"--system", system_, "-o", recording_, "--topics", kRecordedTopics});
    // The recorder subscribed and matched the virtual robot before anything moves.
    EXPECT_TRUE(SpinUntil(
        [&] {
          for (const auto& t : Topics()) {
            if (t.topic == "device/camera/frame" && t.readers >= 1 && t.writers >= 1) return true;
          }
          return false;
        },
        20.0))
        << Outputs();
    // The simulated clock, from the ground truth the recorder records as well.
    std::int64_t sim_ns = 0;
    runtime::Reader<msgs::GroundTruthPubSubType> truths(
        participant(), executor(), "sim/ground_truth",
        [&](const msgs::GroundTruth& g) { sim_ns = g.header().stamp_ns(); });
    auto pipeline = StartPipeline();
    EXPECT_TRUE(SpinUntil([&] { return pose_.has_value(); }, 150.0)) << Outputs();
    const std::string sensed = SensedSequence(*pipeline["stickrep-localizer"]);
    // The recording goes on 2 s of simulated time past the pose: a replay at rate 4 is over
    // in 2 s, and a recording that ends at the very sample that completed the last edge leaves
    // a replay no margin for a camera frame still in flight when the replayer exits.
    const std::int64_t pose_sim_ns = sim_ns;
    EXPECT_TRUE(SpinUntil([&] { return sim_ns > pose_sim_ns + 2'000'000'000; }, 20.0))
        << Outputs();
    StopAllAndExpectCleanExit();
    recorder.ReadLines(true);
    EXPECT_EQ(recorder.exit_code(), 0) << recorder.output();
    EXPECT_NE(recorder.output().find("0 lost on the way"), std::string::npos) << recorder.output();
    return {pose_.value_or(Pose{}), sensed};
  }

  // The recording replayed into the pipeline: the pose and the sequence sensed.
  std::pair<Pose, std::string> Replay(const std::string& rate) {
    // The previous pipeline has left discovery, so the counts below are the new one's (a
    // replay at rate 4 lasts about 2 s: started into a half-connected pipeline, it is over
    // before the localizer hears it).
    EXPECT_TRUE(SpinUntil(
        [&] {
          for (const auto& t : Topics()) {
            if (t.writers > 0 || (t.topic.rfind("device/", 0) == 0 && t.readers > 0)) {
              return false;
            }
          }
          return true;
        },
        20.0))
        << Outputs();
    state_ = msgs::MISSION_WAITING_FOR_COMPONENTS;
    auto pipeline = StartPipeline();
    // Wait until the processes read the device streams and each other's streams, and the
    // executive has heard every process active, so the replay starts into a connected
    // pipeline.
    const std::map<std::string, std::pair<int, int>> wanted = {
        {"device/camera/frame", {0, 1}},  {"device/sonar/echo", {0, 1}},
        {"device/base/encoders", {0, 1}}, {"robot/sonar", {1, 3}},
        {"robot/camera/image", {1, 1}},   {"robot/odometry", {1, 3}},
        {"perception/landmark", {1, 1}}};
    EXPECT_TRUE(SpinUntil(
        [&] {
          std::size_t ready = 0;
          for (const auto& t : Topics()) {
            const auto w = wanted.find(t.topic);
            if (w != wanted.end() && t.writers >= w->second.first &&
                t.readers >= w->second.second) {
              ready++;
            }
          }
          return ready == wanted.size() && state_ != msgs::MISSION_WAITING_FOR_COMPONENTS;
        },
        20.0))
        << Outputs();
    // Forgotten only now: the previous localizer published LOCALIZED until it stopped, and
    // those samples were still being dispatched while its pipeline left discovery (one CI
    // run took such a pose for the replay's and read the new localizer's log too early).
    // The new localizer cannot be localized before the replay starts.
    pose_.reset();
    launch::ChildProcess& replay =
        Start("stickrep-replay", {"--system", system_, recording_, "--rate", rate, "--topics",
                                  kReplayedTopics, "--wait", "20"});
    EXPECT_TRUE(SpinUntil([&] { return pose_.has_value(); }, 150.0)) << Outputs();
    const std::string sensed = SensedSequence(*pipeline["stickrep-localizer"]);
    EXPECT_TRUE(SpinUntil([&] { return replay.Exited(); }, 120.0)) << replay.output();
    replay.ReadLines(true);
    EXPECT_EQ(replay.exit_code(), 0) << replay.output();
    EXPECT_NE(replay.output().find("wheel commands ignored"), std::string::npos) << replay.output();
    EXPECT_EQ(replay.output().find("no reader at the start"), std::string::npos)
        << replay.output();
    StopAllAndExpectCleanExit();
    return {pose_.value_or(Pose{}), sensed};
  }

  std::string system_;
  std::string recording_;
  std::optional<Pose> pose_;
  std::unique_ptr<runtime::Reader<msgs::LocalizationPosePubSubType>> poses_;
  msgs::MissionState state_ = msgs::MISSION_WAITING_FOR_COMPONENTS;
  std::unique_ptr<runtime::Reader<msgs::MissionStatusPubSubType>> mission_;
};

TEST_F(ReplayTest, AReplayedRunRecoversTheLivePoseAtRates1And4AndSensesAlike) {
  const auto [live_pose, live_sensed] = RecordLiveRun();
  ASSERT_FALSE(live_pose.ring.empty()) << "the live run recovered no pose";
  std::cout << "live: " << live_pose << "; sensed " << live_sensed << "\n";
  RecordProperty("live_pose", ::testing::PrintToString(live_pose));

  const auto [pose1, sensed1] = Replay("1");
  EXPECT_EQ(pose1, live_pose) << "rate 1 sensed: " << sensed1 << "\nlive: " << live_sensed;
  const auto [pose4, sensed4] = Replay("4");
  EXPECT_EQ(pose4, live_pose) << "rate 4 sensed: " << sensed4 << "\nlive: " << live_sensed;
  // Replays of one recording sense alike (frames are paired with scans and odometry by time).
  const auto [pose4b, sensed4b] = Replay("4");
  EXPECT_EQ(pose4b, live_pose);
  EXPECT_FALSE(sensed1.empty());
  // At 16 in/s, 24 in is 1.5 s of travel missed before the localizer heard odometry, and
  // 4 in a little more than one frame's travel at 5 frames/s.
  EXPECT_TRUE(SensedAlike(sensed1, sensed4, 24.0, 4.0));
  EXPECT_TRUE(SensedAlike(sensed4, sensed4b, 24.0, 4.0));
  std::cout << "rate 1: " << pose1 << "; sensed " << sensed1 << "\nrate 4: " << pose4 << "; sensed "
            << sensed4 << "\nrate 4 again: " << pose4b << "; sensed " << sensed4b << "\n";
}

}  // namespace
}  // namespace stickrep::test
