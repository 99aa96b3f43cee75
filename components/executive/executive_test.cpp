#include "executive/executive.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "stickrep/map_io.h"
#include "stickrep/test_maps.h"

namespace stickrep::executive {
namespace {

using ::testing::HasSubstr;
using ::testing::Optional;

class ExecutiveTest : public ::testing::Test {
 protected:
  ExecutiveTest() : executive_(map_, Config()) {}
  static MissionConfig Config() {
    MissionConfig c;
    c.required_components = {"localizer"};
    c.travel_speed_ftps = 2.0;
    return c;
  }
  void Localize() {
    executive_.mission().OnComponentActive("localizer");
    executive_.OnLocalized(MapPose{map_.FindRing("box"), 0, +1, 10.0}, "box edge 0");
  }
  map::Map map_ = map::ParseMap(map::testing::kBoxMapYaml, "box.yaml");
  Executive executive_;
};

TEST_F(ExecutiveTest, GoalBeforeThePoseIsKnownIsRefused) {
  executive_.mission().OnComponentActive("localizer");
  EXPECT_THAT(executive_.OnGoal("g", "box/2"), Optional(HasSubstr("the pose is not known yet")));
  EXPECT_EQ(executive_.mission().state(), MissionState::kAligning);
}

TEST_F(ExecutiveTest, GoalNotOnTheMapIsRefusedWithTheReason) {
  Localize();
  EXPECT_THAT(executive_.OnGoal("g", "cellar/2"), Optional(HasSubstr("has no ring 'cellar'")));
  EXPECT_THAT(executive_.OnGoal("g", "box/99"), Optional(HasSubstr("out of range")));
  EXPECT_EQ(executive_.mission().state(), MissionState::kLocalized);
  EXPECT_FALSE(executive_.mission().Motion().move);
}

TEST_F(ExecutiveTest, GoalIntoAnotherHallwayIsRefusedAsNotBuilt) {
  Localize();
  EXPECT_THAT(executive_.OnGoal("g", "strip/1"), Optional(HasSubstr("another hallway")));
}

TEST_F(ExecutiveTest, GoalOnTheRingIsDrivenToAndEndsThere) {
  Localize();
  executive_.OnOdometer(100.0);
  EXPECT_EQ(executive_.OnGoal("g", "box/1"), std::nullopt);
  EXPECT_EQ(executive_.mission().state(), MissionState::kExecutingGoal);
  EXPECT_TRUE(executive_.mission().Motion().move);
  // The maintained pose says the robot is past the door's middle: the goal is reached.
  executive_.OnLocalized(MapPose{map_.FindRing("box"), 1, +1, 30.0}, "box edge 1");
  EXPECT_EQ(executive_.mission().state(), MissionState::kGoalReached);
  EXPECT_FALSE(executive_.mission().Motion().move);
}

TEST_F(ExecutiveTest, GoalBehindIsDrivenToInReverseAndNotTakenAsPassed) {
  Localize();  // box edge 0, travelling in ring order
  executive_.OnOdometer(500.0);
  // The middle of the last edge (5, 100 in) is 60 in behind, 340 in ahead: reached
  // against ring order.
  ASSERT_EQ(executive_.OnGoal("g", "box/5"), std::nullopt);
  EXPECT_EQ(executive_.mission().state(), MissionState::kExecutingGoal);
  EXPECT_LT(executive_.mission().Motion().linear_speed_ftps, 0.0);
  // A pose update before the robot has turned round still says "in ring order": the goal
  // is behind that way, but it is being driven to the other way, and is not reached.
  executive_.OnLocalized(MapPose{map_.FindRing("box"), 0, +1, 10.0}, "box edge 0");
  EXPECT_EQ(executive_.mission().state(), MissionState::kExecutingGoal);
  // Now travelling against ring order, inside edge 5 past its middle: reached.
  executive_.OnLocalized(MapPose{map_.FindRing("box"), 5, -1, 60.0}, "box edge 5");
  EXPECT_EQ(executive_.mission().state(), MissionState::kGoalReached);
}

TEST_F(ExecutiveTest, LostPoseDropsTheGoalAndRecovers) {
  Localize();
  ASSERT_EQ(executive_.OnGoal("g", "box/1"), std::nullopt);
  executive_.OnLost();
  EXPECT_EQ(executive_.mission().state(), MissionState::kRecoveringPose);
  EXPECT_THAT(executive_.OnGoal("g2", "box/1"), Optional(HasSubstr("not known")));
}

}  // namespace
}  // namespace stickrep::executive
