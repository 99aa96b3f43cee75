#include "recovery/pose_recovery.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "recovery/test_support.h"

namespace stickrep::recovery {
namespace {

using map::DoorClass;
using testing::Door;
using testing::Wall;

class PoseRecoveryTest : public ::testing::Test {
 protected:
  PoseRecovery Make(Strategy s) {
    RecoveryConfig c;
    c.strategy = s;
    c.base_tolerance = map::MatchTolerance{0.0, 2.0, 10.0};
    return PoseRecovery(index_, c);
  }
  map::Map map_ = testing::CorridorMap();
  map::MatchIndex index_{map_};
};

TEST_F(PoseRecoveryTest, OneCandidateIsAPose) {
  PoseRecovery r = Make(Strategy::kDeterministic);
  r.Add(Door(DoorClass::k36));
  r.Add(Wall(61));
  EXPECT_EQ(r.Add(Door(DoorClass::k32)), RecoveryStatus::kLocalized);
  ASSERT_TRUE(r.pose());
  EXPECT_EQ(r.pose()->last, 5);
  EXPECT_EQ(r.pose()->dir, +1);
}

TEST_F(PoseRecoveryTest, SeveralCandidatesKeepTravelling) {
  PoseRecovery r = Make(Strategy::kDeterministic);
  r.Add(Door(DoorClass::k36));
  EXPECT_EQ(r.Add(Wall(60)), RecoveryStatus::kAmbiguous);
  EXPECT_EQ(r.candidates().size(), 3u);
}

TEST_F(PoseRecoveryTest, NoHeuristicFailsOnTheFirstMismatch) {
  PoseRecovery r = Make(Strategy::kNone);
  r.Add(Door(DoorClass::k36));
  r.Add(Wall(60));
  EXPECT_EQ(r.Add(Door(DoorClass::k40)), RecoveryStatus::kFailed);
  EXPECT_EQ(r.Add(Wall(75)), RecoveryStatus::kFailed);  // ignored until Reset()
  r.Reset();
  EXPECT_EQ(r.status(), RecoveryStatus::kEmpty);
}

TEST_F(PoseRecoveryTest, DeterministicRecoveryDiscardsTheSequenceAndStartsAgain) {
  PoseRecovery r = Make(Strategy::kDeterministic);
  r.Add(Door(DoorClass::k36));
  r.Add(Wall(60));
  EXPECT_EQ(r.Add(Door(DoorClass::k40)), RecoveryStatus::kEmpty);
  EXPECT_EQ(r.last_event(), RecoveryEvent::kRestarted);
  EXPECT_EQ(r.restarts(), 1u);
  EXPECT_TRUE(r.sequence().empty());
}

TEST_F(PoseRecoveryTest, FirstWallAfterARestartIsALowerBound) {
  PoseRecovery r = Make(Strategy::kDeterministic);
  r.Add(Door(DoorClass::k36));
  r.Add(Wall(60));
  r.Add(Door(DoorClass::k40));
  r.Add(Wall(40));  // only part of a wall may have been seen
  ASSERT_EQ(r.sequence().size(), 1u);
  EXPECT_TRUE(r.sequence()[0].metric_is_lower_bound);
  EXPECT_EQ(r.status(), RecoveryStatus::kAmbiguous);
}

TEST_F(PoseRecoveryTest, FirstFrameHeuristicRestartsOnAnEarlyFailure) {
  PoseRecovery r = Make(Strategy::kFirstFrame);
  r.Add(Door(DoorClass::k32));
  EXPECT_EQ(r.Add(Wall(90)), RecoveryStatus::kEmpty);
  EXPECT_EQ(r.restarts(), 1u);
}

TEST_F(PoseRecoveryTest, FirstFrameHeuristicFailsOnALateFailure) {
  PoseRecovery r = Make(Strategy::kFirstFrame);
  r.Add(Door(DoorClass::k36));
  r.Add(Wall(60));
  EXPECT_EQ(r.Add(Door(DoorClass::k40)), RecoveryStatus::kFailed);
}

TEST_F(PoseRecoveryTest, MetricRelaxationStepsUpUntilTheWallMatches) {
  PoseRecovery r = Make(Strategy::kRelaxation);
  r.Add(Door(DoorClass::k40));
  EXPECT_EQ(r.Add(Wall(98)), RecoveryStatus::kLocalized);  // W90 is 8.9 % short
  EXPECT_EQ(r.last_event(), RecoveryEvent::kRelaxed);
  EXPECT_DOUBLE_EQ(r.wall_relaxation(), 0.10);
  EXPECT_EQ(r.pose()->last, 8);
}

TEST_F(PoseRecoveryTest, MetricRelaxationFailsBeyondTwentyPercent) {
  PoseRecovery r = Make(Strategy::kRelaxation);
  r.Add(Door(DoorClass::k40));
  EXPECT_EQ(r.Add(Wall(300)), RecoveryStatus::kFailed);  // 50 % off the longest wall
}

TEST_F(PoseRecoveryTest, MissizedHeuristicRelaxesDoorClassesOnly) {
  PoseRecovery r = Make(Strategy::kMissized);
  r.Add(Door(DoorClass::k32, 33.5));  // a 36 in door classed 32
  EXPECT_EQ(r.Add(Wall(75)), RecoveryStatus::kLocalized);
  EXPECT_DOUBLE_EQ(r.door_relaxation(), 0.10);
  EXPECT_DOUBLE_EQ(r.wall_relaxation(), 0.0);
  EXPECT_EQ(r.pose()->last, 10);
}

TEST_F(PoseRecoveryTest, FalseDoorHeuristicRemovesTheLeastLikelyClass) {
  PoseRecovery r = Make(Strategy::kFalseDoor);
  // Starts inside the 200 in wall, passes the 40 in door, then a false 32 in door splits
  // the 90 in wall into 30 + 32 + 28.
  const map::SensedEdge first[] = {Wall(150, std::numeric_limits<double>::quiet_NaN(), true),
                                   Door(DoorClass::k40)};
  EXPECT_EQ(r.AddEdges(first, 2), RecoveryStatus::kLocalized);  // the corner rules out 11
  const map::SensedEdge second[] = {Wall(30), Door(DoorClass::k32)};
  EXPECT_EQ(r.AddEdges(second, 2), RecoveryStatus::kLocalized);
  EXPECT_EQ(r.last_event(), RecoveryEvent::kDoorsRemoved);
  EXPECT_EQ(r.removed_doors(), 1u);
  EXPECT_EQ(r.Add(Wall(28)), RecoveryStatus::kLocalized);  // 30 + 32 + 28 = 90
  EXPECT_EQ(r.pose()->last, 8);
  EXPECT_EQ(r.pose()->dir, +1);
}

TEST_F(PoseRecoveryTest, FalseDoorHeuristicTargetsTheRarestClassOfTheMap) {
  PoseRecovery r = Make(Strategy::kFalseDoor);
  const auto& codes = r.removable_codes();
  EXPECT_NE(std::find(codes.begin(), codes.end(), map::DoorCode(DoorClass::k32)), codes.end());
  EXPECT_EQ(std::find(codes.begin(), codes.end(), map::DoorCode(DoorClass::k36)), codes.end());
  EXPECT_EQ(std::find(codes.begin(), codes.end(), map::DoorCode(DoorClass::k40)), codes.end());
}

TEST_F(PoseRecoveryTest, FullSuiteRestartsInTheFirstFrame) {
  PoseRecovery r = Make(Strategy::kFullSuite);
  r.Add(Door(DoorClass::k32));
  EXPECT_EQ(r.Add(Wall(90)), RecoveryStatus::kEmpty);
  EXPECT_EQ(r.last_event(), RecoveryEvent::kRestarted);
}

TEST_F(PoseRecoveryTest, FullSuiteRelaxesLaterFailures) {
  PoseRecovery r = Make(Strategy::kFullSuite);
  r.Add(Wall(150, std::numeric_limits<double>::quiet_NaN(), true));
  r.Add(Door(DoorClass::k40));
  EXPECT_EQ(r.Add(Wall(98)), RecoveryStatus::kLocalized);
  EXPECT_EQ(r.last_event(), RecoveryEvent::kRelaxed);
}

TEST_F(PoseRecoveryTest, InvalidEdgesAreRejectedAndCounted) {
  PoseRecovery r = Make(Strategy::kDeterministic);
  map::SensedEdge nan_door = Door(DoorClass::k36);
  nan_door.metric_in = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(r.Add(nan_door), RecoveryStatus::kEmpty);
  EXPECT_EQ(r.last_event(), RecoveryEvent::kRejected);
  map::SensedEdge negative = Wall(-3);
  r.Add(negative);
  map::SensedEdge unknown = Wall(10);
  unknown.code = 42;
  r.Add(unknown);
  EXPECT_EQ(r.rejected(), 3u);
  EXPECT_TRUE(r.sequence().empty());
}

TEST_F(PoseRecoveryTest, CheckSensedEdgeSaysWhy) {
  map::SensedEdge e = Door(DoorClass::k36);
  EXPECT_FALSE(CheckSensedEdge(e));
  e.metric_in = std::nan("");
  ASSERT_TRUE(CheckSensedEdge(e));
  EXPECT_NE(CheckSensedEdge(e)->find("NaN"), std::string::npos);
}

TEST(StrategyNames, RoundTrip) {
  for (const Strategy s : kAllStrategies) EXPECT_EQ(ParseStrategy(StrategyName(s)), s);
  EXPECT_FALSE(ParseStrategy("magic"));
}

}  // namespace
}  // namespace stickrep::recovery
