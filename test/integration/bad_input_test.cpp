// Bad input to a running system, each process on its own: goals the executive cannot take
// are refused with the reason on mission/status, and a motion command with a NaN speed
// stops the base with locomotion saying why.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <optional>

#include "basePubSubTypes.h"
#include "integration/process_fixture.h"
#include "localizationPubSubTypes.h"
#include "missionPubSubTypes.h"
#include "runtime/process.h"

namespace stickrep::test {
namespace {

using ::testing::HasSubstr;

class BadInputTest : public ProcessFixture {
 protected:
  BadInputTest() : ProcessFixture(27) {}
};

TEST_F(BadInputTest, GoalsTheExecutiveCannotTakeAreRefusedWithTheReason) {
  std::vector<msgs::MissionStatus> statuses;
  std::optional<msgs::MotionCommand> last_command;
  runtime::Reader<msgs::MissionStatusPubSubType> status(
      participant(), executor(), "mission/status",
      [&](const msgs::MissionStatus& s) { statuses.push_back(s); });
  runtime::Reader<msgs::MotionCommandPubSubType> commands(
      participant(), executor(), "robot/motion/command",
      [&](const msgs::MotionCommand& m) { last_command = m; });
  std::map<std::string, msgs::MissionGoalResult> results;  // by goal id
  runtime::Reader<msgs::MissionGoalResultPubSubType> result_reader(
      participant(), executor(), "mission/goal_result",
      [&](const msgs::MissionGoalResult& r) { results[r.goal_id()] = r; });
  runtime::Writer<msgs::MissionGoalPubSubType> goals(participant(), "mission/goal");
  runtime::Writer<msgs::LocalizationPosePubSubType> poses(participant(), "localization/pose");
  // The executive alone, needing no other process: it starts aligning once it is active.
  const std::string config = WriteTempFile(
      "executive.yaml",
      "executive:\n  required_components: []\n  travel_speed_ftps: 2.6\n  travel_direction: 1\n"
      "  align_speed_ftps: 1.3\n  aligned_hold_s: 1.0\n  align_timeout_s: 30\n"
      "  command_rate_hz: 10\n  heartbeat_timeout_s: 3.0\n  link_settle_s: 2.0\n"
      "  exit_when_localized: false\n");
  Start("stickrep-executive", {"--config", config});
  ASSERT_TRUE(SpinUntil(
      [&] { return !statuses.empty() && statuses.back().state() == msgs::MISSION_ALIGNING; }, 20.0))
      << Outputs();

  // Sends a goal until a status names it; returns that status.
  const auto send = [&](const std::string& id, const std::string& target) {
    msgs::MissionGoal g;
    g.goal_id(id);
    g.target(target);
    std::optional<msgs::MissionStatus> reply;
    SpinUntil(
        [&] {
          goals.Publish(g, runtime::WallClockNowNs());
          SpinUntil(
              [&] {
                return !statuses.empty() &&
                       statuses.back().message().find("'" + id + "'") != std::string::npos;
              },
              0.5);
          if (!statuses.empty() &&
              statuses.back().message().find("'" + id + "'") != std::string::npos) {
            reply = statuses.back();
          }
          return reply.has_value();
        },
        20.0);
    return reply;
  };

  // Before the pose is known.
  auto reply = send("early", "wing1_corridor/10");
  ASSERT_TRUE(reply.has_value()) << Outputs();
  EXPECT_THAT(reply->message(), HasSubstr("refused: the pose is not known yet"));
  EXPECT_EQ(reply->state(), msgs::MISSION_ALIGNING);
  // The structured answer: the goal's id, refused, and why.
  ASSERT_TRUE(SpinUntil([&] { return results.count("early") > 0; }, 5.0));
  EXPECT_FALSE(results["early"].accepted());
  EXPECT_EQ(results["early"].target(), "wing1_corridor/10");
  EXPECT_THAT(results["early"].reason(), HasSubstr("the pose is not known yet"));

  // Localized (as the localizer would say): goals now name places, or are refused.
  msgs::LocalizationPose pose;
  pose.status(msgs::LOCALIZATION_LOCALIZED);
  pose.candidate_count(1);
  pose.best().ring_id("wing1_corridor");
  pose.best().edge_index(20);
  pose.best().forward(false);
  pose.best().offset_in(10.0);
  ASSERT_TRUE(SpinUntil(
      [&] {
        poses.Publish(pose, runtime::WallClockNowNs());
        return !statuses.empty() && statuses.back().state() == msgs::MISSION_LOCALIZED;
      },
      20.0))
      << Outputs();
  ASSERT_TRUE(
      SpinUntil([&] { return last_command && last_command->mode() == msgs::MOTION_STOP; }, 5.0));

  reply = send("nowhere", "library/3");
  ASSERT_TRUE(reply.has_value());
  EXPECT_THAT(reply->message(), HasSubstr("refused"));
  EXPECT_THAT(reply->message(), HasSubstr("has no ring 'library'"));
  reply = send("too-far", "wing1_corridor/500");
  ASSERT_TRUE(reply.has_value());
  EXPECT_THAT(reply->message(), HasSubstr("edge 500 is out of range"));
  reply = send("garbled", "wing1_corridor//x");
  ASSERT_TRUE(reply.has_value());
  EXPECT_THAT(reply->message(), HasSubstr("refused"));
  // The console's goal verb reads the structured answer: refused, exit 1, with the reason.
  launch::ChildProcess& console = Start(
      "stickrep-console", {"goal", "library/3", "--id", "from-console", "--timeout", "15"});
  ASSERT_TRUE(SpinUntil([&] { return console.Exited(); }, 30.0)) << Outputs();
  console.ReadLines(true);
  EXPECT_EQ(console.exit_code(), 1) << console.output();
  EXPECT_THAT(console.output(), HasSubstr("goal 'from-console' (library/3): refused: "));
  EXPECT_THAT(console.output(), HasSubstr("has no ring 'library'"));
  // The robot keeps its safe state: still holding, still commanded to stop.
  EXPECT_EQ(statuses.back().state(), msgs::MISSION_LOCALIZED);
  SpinUntil([] { return false; }, 0.3);
  EXPECT_EQ(last_command->mode(), msgs::MOTION_STOP);

  // A door on the map is taken: the robot follows the hallway toward it.
  reply = send("door", "wing1_corridor/15");
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->state(), msgs::MISSION_EXECUTING_GOAL) << reply->message();
  ASSERT_TRUE(SpinUntil([&] { return results.count("door") > 0; }, 5.0));
  EXPECT_TRUE(results["door"].accepted()) << results["door"].reason();
  ASSERT_TRUE(SpinUntil(
      [&] { return last_command && last_command->mode() == msgs::MOTION_FOLLOW_HALLWAY; }, 5.0));
  EXPECT_GT(std::abs(last_command->linear_speed_ftps()), 0.0);
  StopAllAndExpectCleanExit();
}

TEST_F(BadInputTest, MotionCommandWithANanSpeedStopsTheBaseAndSaysWhy) {
  std::optional<msgs::MotionState> state;
  double odometer_in = 0.0, speed_ftps = -1.0;
  runtime::Reader<msgs::MotionStatePubSubType> states(
      participant(), executor(), "robot/motion/state",
      [&](const msgs::MotionState& s) { state = s; });
  runtime::Reader<msgs::OdometryPubSubType> odometry(participant(), executor(), "robot/odometry",
                                                     [&](const msgs::Odometry& o) {
                                                       odometer_in = o.distance_in();
                                                       speed_ftps = o.linear_speed_ftps();
                                                     });
  runtime::Writer<msgs::MotionCommandPubSubType> commands(participant(), "robot/motion/command");
  double speed = 1.3;
  executor().AddTimer(0.1, [&] {
    msgs::MotionCommand m;
    m.mode(msgs::MOTION_FOLLOW_HALLWAY);
    m.linear_speed_ftps(speed);
    commands.Publish(m, runtime::WallClockNowNs());
  });
  Start("stickrep-virtual-robot");
  Start("stickrep-sonar");
  Start("stickrep-locomotion");
  ASSERT_TRUE(SpinUntil([&] { return odometer_in > 12.0; }, 40.0)) << Outputs();
  ASSERT_TRUE(state.has_value());
  EXPECT_EQ(state->mode(), msgs::MOTION_FOLLOW_HALLWAY);

  speed = std::numeric_limits<double>::quiet_NaN();
  ASSERT_TRUE(SpinUntil(
      [&] { return state && state->state() == msgs::LOCOMOTION_STOPPED && speed_ftps == 0.0; },
      10.0))
      << Outputs();
  EXPECT_THAT(state->message(), HasSubstr("non-finite"));
  const double stopped_at = odometer_in;
  SpinUntil([] { return false; }, 1.0);
  EXPECT_LT(odometer_in - stopped_at, 1.0);

  // Good commands again: the base follows the hallway again.
  speed = 1.3;
  ASSERT_TRUE(SpinUntil([&] { return odometer_in > stopped_at + 6.0; }, 20.0)) << Outputs();
  StopAllAndExpectCleanExit();
}

}  // namespace
}  // namespace stickrep::test
