#include "executive/mission.h"

#include <gtest/gtest.h>

#include <set>

namespace stickrep::executive {
namespace {

MissionConfig TwoComponents() {
  MissionConfig c;
  c.required_components = {"sonar", "localizer"};
  c.travel_speed_ftps = 2.0;
  return c;
}

TEST(MissionTest, WaitsUntilEveryRequiredProcessIsActiveBeforeMoving) {
  Mission m(TwoComponents());
  m.OnComponentActive("sonar");
  EXPECT_EQ(m.state(), MissionState::kWaitingForComponents);
  EXPECT_FALSE(m.Motion().move);
  m.OnComponentActive("localizer");
  EXPECT_EQ(m.state(), MissionState::kAligning);
  EXPECT_TRUE(m.Motion().move);
  EXPECT_DOUBLE_EQ(m.Motion().linear_speed_ftps, 1.3);
}

TEST(MissionTest, AlignsUntilInsideTheEnvelopeLongEnoughThenTravelsAtFullSpeed) {
  Mission m(TwoComponents());
  m.OnComponentActive("sonar");
  m.OnComponentActive("localizer");
  m.OnMotionState(false, 100.0);
  m.OnMotionState(true, 101.0);
  m.OnMotionState(false, 101.5);  // out again: the hold starts over
  m.OnMotionState(true, 102.0);
  m.OnMotionState(true, 102.9);
  EXPECT_EQ(m.state(), MissionState::kAligning);
  m.OnMotionState(true, 103.0);
  EXPECT_EQ(m.state(), MissionState::kRecoveringPose);
  EXPECT_DOUBLE_EQ(m.Motion().linear_speed_ftps, 2.0);
}

TEST(MissionTest, AligningThatTakesTooLongGivesWayToRecoveryAndSaysSo) {
  Mission m(TwoComponents());
  m.OnComponentActive("sonar");
  m.OnComponentActive("localizer");
  m.OnMotionState(false, 10.0);
  m.OnMotionState(false, 39.0);
  EXPECT_EQ(m.state(), MissionState::kAligning);
  m.OnMotionState(false, 40.0);
  EXPECT_EQ(m.state(), MissionState::kRecoveringPose);
  EXPECT_NE(m.last_message().find("anyway"), std::string::npos) << m.last_message();
}

TEST(MissionTest, MotionReportsOutsideAligningChangeNothing) {
  Mission m(TwoComponents());
  m.OnMotionState(true, 0.0);
  m.OnMotionState(true, 50.0);
  EXPECT_EQ(m.state(), MissionState::kWaitingForComponents);
}

TEST(MissionTest, LocalizedStopsTheRobotUntilAGoalArrives) {
  Mission m(TwoComponents());
  m.OnComponentActive("sonar");
  m.OnComponentActive("localizer");
  m.OnLocalized("ring a edge 3");
  EXPECT_EQ(m.state(), MissionState::kLocalized);
  EXPECT_FALSE(m.Motion().move);
  EXPECT_FALSE(m.CanTakeGoal().has_value());
}

TEST(MissionTest, GoalBeforeThePoseIsKnownIsRefusedWithTheReason) {
  Mission m(TwoComponents());
  m.OnComponentActive("sonar");
  m.OnComponentActive("localizer");
  ASSERT_TRUE(m.CanTakeGoal().has_value());
  EXPECT_EQ(*m.CanTakeGoal(), "the pose is not known yet");
}

TEST(MissionTest, GoalIsDrivenToByOdometryAndThenTheRobotStops) {
  Mission m(TwoComponents());
  m.OnComponentActive("sonar");
  m.OnComponentActive("localizer");
  m.OnLocalized("x");
  m.StartGoal(GoalPlan{"g1", "back 100 in", -1, 100.0}, 500.0);
  EXPECT_EQ(m.state(), MissionState::kExecutingGoal);
  EXPECT_DOUBLE_EQ(m.Motion().linear_speed_ftps, -2.0);
  m.OnOdometer(450.0);
  EXPECT_EQ(m.state(), MissionState::kExecutingGoal);
  m.OnOdometer(399.0);
  EXPECT_EQ(m.state(), MissionState::kGoalReached);
  EXPECT_FALSE(m.Motion().move);
}

TEST(MissionTest, TheLocalizedPoseReanchorsTheGoal) {
  Mission m(TwoComponents());
  m.OnComponentActive("sonar");
  m.OnComponentActive("localizer");
  m.OnLocalized("x");
  m.StartGoal(GoalPlan{"g1", "ahead 300 in", +1, 300.0}, 0.0);
  // Odometry says 250 in to go; the maintained pose says 20 in: it wins.
  m.UpdateGoal(20.0, 50.0);
  m.OnOdometer(65.0);
  EXPECT_EQ(m.state(), MissionState::kExecutingGoal);
  m.OnOdometer(71.0);
  EXPECT_EQ(m.state(), MissionState::kGoalReached);
}

TEST(MissionTest, APoseBeyondTheGoalEndsItAtOnce) {
  Mission m(TwoComponents());
  m.OnComponentActive("sonar");
  m.OnComponentActive("localizer");
  m.OnLocalized("x");
  m.StartGoal(GoalPlan{"g1", "ahead 300 in", +1, 300.0}, 0.0);
  m.UpdateGoal(-5.0, 200.0);
  EXPECT_EQ(m.state(), MissionState::kGoalReached);
}

TEST(MissionTest, RequiredProcessGoneStopsTheRobotUntilItIsBackAndThePoseIsKept) {
  Mission m(TwoComponents());
  m.OnComponentActive("sonar");
  m.OnComponentActive("localizer");
  m.OnLocalized("x");
  m.OnComponentGone("sonar", "liveliness lost");
  EXPECT_EQ(m.state(), MissionState::kStoppedFault);
  EXPECT_FALSE(m.Motion().move);
  EXPECT_EQ(m.Absent(), (std::set<std::string>{"sonar"}));
  EXPECT_NE(m.CanTakeGoal(), std::nullopt);
  m.OnComponentActive("sonar");
  EXPECT_EQ(m.state(), MissionState::kLocalized);
  EXPECT_NE(m.last_message().find("pose kept"), std::string::npos) << m.last_message();
  EXPECT_TRUE(m.Absent().empty());
}

TEST(MissionTest, AProcessThatIsNotRequiredChangesNothingWhenItGoes) {
  Mission m(TwoComponents());
  m.OnComponentActive("sonar");
  m.OnComponentActive("localizer");
  m.OnComponentGone("camera", "liveliness lost");
  EXPECT_EQ(m.state(), MissionState::kAligning);
}

TEST(MissionTest, TheLocalizerBackAfterAFaultMeansRecoveringThePoseAgain) {
  Mission m(TwoComponents());
  m.OnComponentActive("sonar");
  m.OnComponentActive("localizer");
  m.OnLocalized("x");
  m.OnComponentGone("localizer", "liveliness lost");
  m.OnComponentActive("localizer");
  EXPECT_EQ(m.state(), MissionState::kRecoveringPose);
  EXPECT_TRUE(m.Motion().move);
  EXPECT_NE(m.last_message().find("localizer restarted"), std::string::npos) << m.last_message();
  m.OnLocalized("y");
  EXPECT_EQ(m.state(), MissionState::kLocalized);
}

TEST(MissionTest, EveryAbsentProcessMustBeBackBeforeTheRobotMovesAgain) {
  Mission m = [] {
    Mission r(TwoComponents());
    r.OnComponentActive("sonar");
    r.OnComponentActive("localizer");
    r.OnMotionState(true, 0.0);
    r.OnMotionState(true, 1.0);
    return r;
  }();
  ASSERT_EQ(m.state(), MissionState::kRecoveringPose);
  m.OnComponentGone("sonar", "liveliness lost");
  m.OnComponentGone("localizer", "no heartbeat for 2.0 s");
  EXPECT_NE(m.last_message().find("'localizer', 'sonar' are back"), std::string::npos)
      << m.last_message();
  m.OnComponentActive("sonar");
  EXPECT_EQ(m.state(), MissionState::kStoppedFault);
  EXPECT_FALSE(m.Motion().move);
  m.OnComponentActive("localizer");
  EXPECT_EQ(m.state(), MissionState::kRecoveringPose);
  EXPECT_TRUE(m.Motion().move);
}

// A process restarted faster than the base can brake: the fault stop still completes.
TEST(MissionTest, AfterAFaultTheRobotMovesAgainOnlyOnceTheBaseHasBeenAtRest) {
  Mission m(TwoComponents());
  m.OnComponentActive("sonar");
  m.OnComponentActive("localizer");
  m.OnMotionState(true, 0.0);
  m.OnMotionState(true, 1.0);
  ASSERT_EQ(m.state(), MissionState::kRecoveringPose);
  m.OnBaseSpeed(2.0, 10.0);
  m.OnComponentGone("localizer", "it restarted");
  m.OnComponentActive("localizer");  // back at once, the base still braking
  EXPECT_EQ(m.state(), MissionState::kStoppedFault);
  EXPECT_FALSE(m.Motion().move);
  EXPECT_NE(m.last_message().find("waiting for the base to come to rest"), std::string::npos)
      << m.last_message();
  m.OnBaseSpeed(0.5, 10.5);
  m.OnBaseSpeed(0.0, 11.0);
  m.OnBaseSpeed(0.3, 11.1);  // not at rest after all: the hold starts over
  m.OnBaseSpeed(0.0, 11.2);
  m.OnBaseSpeed(0.0, 11.2 + Mission::kFaultRestHoldS / 2);
  EXPECT_EQ(m.state(), MissionState::kStoppedFault);
  m.OnBaseSpeed(0.0, 11.2 + Mission::kFaultRestHoldS);
  EXPECT_EQ(m.state(), MissionState::kRecoveringPose);
  EXPECT_NE(m.last_message().find("localizer restarted"), std::string::npos) << m.last_message();
  EXPECT_TRUE(m.Motion().move);
}

TEST(MissionTest, ABaseAlreadyHeldAtRestLetsTheMissionResumeAsSoonAsTheProcessIsBack) {
  Mission m(TwoComponents());
  m.OnComponentActive("sonar");
  m.OnComponentActive("localizer");
  m.OnLocalized("x");
  m.OnBaseSpeed(0.0, 5.0);
  m.OnComponentGone("sonar", "no heartbeat for 2.0 s");
  m.OnBaseSpeed(0.0, 5.0 + Mission::kFaultRestHoldS);
  EXPECT_EQ(m.state(), MissionState::kStoppedFault);  // sonar still absent
  m.OnComponentActive("sonar");
  EXPECT_EQ(m.state(), MissionState::kLocalized);
}

TEST(MissionTest, AGoalInProgressContinuesAfterAFaultThatKeptThePose) {
  Mission m(TwoComponents());
  m.OnComponentActive("sonar");
  m.OnComponentActive("localizer");
  m.OnLocalized("x");
  m.StartGoal(GoalPlan{"g1", "ahead 300 in", +1, 300.0}, 0.0);
  m.OnComponentGone("sonar", "liveliness lost");
  m.OnOdometer(400.0);  // odometry of a base at rest does not end the goal meanwhile
  EXPECT_EQ(m.state(), MissionState::kStoppedFault);
  m.OnComponentActive("sonar");
  EXPECT_EQ(m.state(), MissionState::kExecutingGoal);
  m.OnOdometer(400.0);
  EXPECT_EQ(m.state(), MissionState::kGoalReached);
}

TEST(MissionTest, APoseLostDuringAFaultIsRecoveredAfterIt) {
  Mission m(TwoComponents());
  m.OnComponentActive("sonar");
  m.OnComponentActive("localizer");
  m.OnLocalized("x");
  m.OnComponentGone("sonar", "liveliness lost");
  m.OnLost();
  m.OnComponentActive("sonar");
  EXPECT_EQ(m.state(), MissionState::kRecoveringPose);
}

TEST(MissionTest, ARestartedExecutiveHoldsThePoseTheLocalizerKept) {
  Mission m(TwoComponents());
  m.OnLocalized("ring a edge 3");  // the localizer's latched pose, before the heartbeats
  m.OnComponentActive("sonar");
  EXPECT_EQ(m.state(), MissionState::kWaitingForComponents);
  m.OnComponentActive("localizer");
  EXPECT_EQ(m.state(), MissionState::kLocalized);
  EXPECT_FALSE(m.Motion().move);
  EXPECT_NE(m.last_message().find("ring a edge 3"), std::string::npos) << m.last_message();
}

TEST(MissionTest, LostPoseStartsRecoveryAgain) {
  Mission m(TwoComponents());
  m.OnComponentActive("sonar");
  m.OnComponentActive("localizer");
  m.OnLocalized("x");
  m.OnLost();
  EXPECT_EQ(m.state(), MissionState::kRecoveringPose);
}

Mission Recovering() {
  Mission m(TwoComponents());
  m.OnComponentActive("sonar");
  m.OnComponentActive("localizer");
  m.OnMotionState(true, 0.0);
  m.OnMotionState(true, 1.0);
  return m;
}

TEST(MissionTest, LinkLostStopsTheRobotAndRecoveryContinuesWhenItIsBack) {
  Mission m = Recovering();
  ASSERT_EQ(m.state(), MissionState::kRecoveringPose);
  m.OnLinkLost("robot", "no process on host 'robot' heard for 2.1 s");
  EXPECT_EQ(m.state(), MissionState::kLinkLost);
  EXPECT_FALSE(m.Motion().move);
  EXPECT_NE(m.CanTakeGoal(), std::nullopt);
  m.OnLinkBack("robot", 3.4, false);
  EXPECT_EQ(m.state(), MissionState::kRecoveringPose);
  EXPECT_NE(m.last_message().find("back after 3.4 s"), std::string::npos);
  EXPECT_TRUE(m.Motion().move);
}

TEST(MissionTest, LinkBackKeepsThePoseWhenTheLocalizerStillHasIt) {
  Mission m = Recovering();
  m.OnLocalized("ring a edge 3");
  m.OnLinkLost("robot", "silent");
  m.OnLinkBack("robot", 60.2, true);
  EXPECT_EQ(m.state(), MissionState::kLocalized);
  EXPECT_NE(m.last_message().find("pose kept"), std::string::npos);
}

TEST(MissionTest, LinkBackWithoutThePoseReacquiresItAndSaysSo) {
  Mission m = Recovering();
  m.OnLocalized("ring a edge 3");
  m.OnLinkLost("robot", "silent");
  m.OnLinkBack("robot", 5.0, false);
  EXPECT_EQ(m.state(), MissionState::kRecoveringPose);
  EXPECT_NE(m.last_message().find("re-acquire"), std::string::npos);
}

TEST(MissionTest, APoseRecoveredDuringTheLinkLossIsHeldOnceItIsBack) {
  Mission m = Recovering();
  m.OnLinkLost("robot", "silent");
  m.OnLocalized("ring a edge 3");
  EXPECT_EQ(m.state(), MissionState::kLinkLost);
  EXPECT_FALSE(m.Motion().move);
  m.OnLinkBack("robot", 3.0, true);
  EXPECT_EQ(m.state(), MissionState::kLocalized);
}

TEST(MissionTest, AProcessGoneDuringTheLinkLossIsAFault) {
  Mission m = Recovering();
  m.OnLinkLost("robot", "silent");
  m.OnComponentGone("sonar", "it did not come back with its host");
  EXPECT_EQ(m.state(), MissionState::kStoppedFault);
  m.OnLinkBack("robot", 3.0, true);
  EXPECT_EQ(m.state(), MissionState::kStoppedFault);
}

TEST(MissionTest, TransitionsAreRecordedInOrder) {
  Mission m(TwoComponents());
  m.OnComponentActive("sonar");
  m.OnComponentActive("localizer");
  m.OnLocalized("x");
  const auto t = m.TakeTransitions();
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[0].rfind("WAITING_FOR_COMPONENTS -> ALIGNING", 0), 0u);
  EXPECT_EQ(t[1].rfind("ALIGNING -> LOCALIZED", 0), 0u);
  EXPECT_TRUE(m.TakeTransitions().empty());
}

}  // namespace
}  // namespace stickrep::executive
