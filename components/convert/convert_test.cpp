#include "convert/convert.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace stickrep::convert {
namespace {

TEST(ConvertTest, SonarScanRoundTripsAndRefusesAnEchoWithoutARange) {
  message::SonarScan s;
  s.header = {1234, 0};
  s.state.fill(sonar::ReadingState::kNoEcho);
  s.range_in[3] = 48.5f;
  s.state[3] = sonar::ReadingState::kValid;
  s.state[4] = sonar::ReadingState::kNoEcho;
  s.valid_count = 1;
  msgs::SonarScan m = ToIdl(s);
  const auto back = FromIdl(m);
  ASSERT_TRUE(back.value) << back.reason;
  EXPECT_EQ(back.value->header.stamp_ns, 1234);
  EXPECT_FLOAT_EQ(back.value->range_in[3], 48.5f);
  EXPECT_EQ(back.value->state[4], sonar::ReadingState::kNoEcho);

  m.range_in()[3] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(FromIdl(m).reason, "a reading with an echo is not a positive range");
  m.range_in()[3] = 48.5f;
  m.reading_state()[5] = static_cast<msgs::SonarReadingState>(9);
  EXPECT_EQ(FromIdl(m).reason, "a reading state out of range");
}

TEST(ConvertTest, LandmarkClassesMapOneToOneAndRejectedIsRefused) {
  for (int c = 0; c < 6; ++c) {
    message::LandmarkObservation o;
    o.door_class = static_cast<sensing::DoorClass>(c);
    o.width_in = 30.0;
    const auto back = FromIdl(ToIdl(o));
    ASSERT_TRUE(back.value) << back.reason;
    EXPECT_EQ(back.value->door_class, o.door_class);
  }
  msgs::LandmarkObservation m;
  m.door_class(msgs::DOOR_REJECTED);
  m.width_in(30.0);
  EXPECT_EQ(FromIdl(m).reason, "not a door class");
  m.door_class(msgs::DOOR_36);
  m.width_in(-1.0);
  EXPECT_EQ(FromIdl(m).reason, "non-finite or non-positive width or position");
  m.width_in(36.0);
  m.mark(static_cast<msgs::DoorMark>(7));  // an outside writer's value beyond the enum
  EXPECT_EQ(FromIdl(m).reason, "not a door mark");
  for (const map::DoorMark mark : {map::DoorMark::kUnknown, map::DoorMark::kPlain,
                                   map::DoorMark::kWindow, map::DoorMark::kPoster}) {
    message::LandmarkObservation o;
    o.width_in = 36.0;
    o.mark = mark;
    const auto back = FromIdl(ToIdl(o));
    ASSERT_TRUE(back.value) << back.reason;
    EXPECT_EQ(back.value->mark, mark);
  }
}

TEST(ConvertTest, OdometryAndWheelsRefuseNonFiniteValues) {
  msgs::Odometry o;
  o.distance_in(std::numeric_limits<double>::infinity());
  EXPECT_EQ(FromIdl(o).reason, "non-finite distance");
  o.distance_in(10.0);
  o.pose().heading_rad(std::nan(""));
  EXPECT_EQ(FromIdl(o).reason, "non-finite heading");
  o.pose().heading_rad(0.0);
  o.linear_speed_ftps(-std::numeric_limits<double>::infinity());
  EXPECT_EQ(FromIdl(o).reason, "non-finite speed");
  msgs::WheelCommand w;
  w.left_speed_ftps(std::nan(""));
  EXPECT_FALSE(FromIdl(w).value);
}

TEST(ConvertTest, MotionCommandPassesANonFiniteSpeedButNotABadMode) {
  msgs::MotionCommand m;
  m.mode(msgs::MOTION_FOLLOW_HALLWAY);
  m.linear_speed_ftps(std::nan(""));
  const auto c = FromIdl(m);
  ASSERT_TRUE(c.value);
  EXPECT_EQ(c.value->mode, message::MotionMode::kFollowHallway);
  m.mode(static_cast<msgs::MotionMode>(7));
  EXPECT_EQ(FromIdl(m).reason, "a motion mode out of range");
}

TEST(ConvertTest, PoseKeepsTheBestHypothesisAndHypothesesKeepTheirOrder) {
  message::LocalizationPose p;
  p.status = message::LocalizationStatus::kLocalized;
  p.best = {"main", 7, false, 12.5, 1.0, 2.0, 0.5, 0.99};
  const auto back = FromIdl(ToIdl(p));
  ASSERT_TRUE(back.value);
  EXPECT_EQ(back.value->status, message::LocalizationStatus::kLocalized);
  EXPECT_EQ(back.value->best.ring_id, "main");
  EXPECT_EQ(back.value->best.edge_index, 7);
  EXPECT_FALSE(back.value->best.forward);
  message::PoseHypotheses hs;
  hs.hypotheses = {p.best, {"wing", 2, true, 0, 0, 0, 0, 0.01}};
  const auto hb = FromIdl(ToIdl(hs));
  ASSERT_EQ(hb.value->hypotheses.size(), 2u);
  EXPECT_EQ(hb.value->hypotheses[1].ring_id, "wing");
}

TEST(ConvertTest, StatusEnumsOutOfRangeAreRefused) {
  msgs::LocalizationPose p;
  p.status(static_cast<msgs::LocalizationStatus>(5));
  EXPECT_FALSE(FromIdl(p).value);
  msgs::ComponentStatus s;
  s.state(static_cast<msgs::ComponentState>(9));
  EXPECT_FALSE(FromIdl(s).value);
  msgs::MissionStatus ms;
  ms.state(msgs::MISSION_LINK_LOST);
  EXPECT_EQ(FromIdl(ms).value->state, message::MissionState::kLinkLost);
}

TEST(ConvertTest, GroundTruthRoundTripsAndRefusesANonFinitePose) {
  message::GroundTruth g;
  g.header = {99, 0};
  g.x_in = 12.5;
  g.y_in = -3.0;
  g.heading_rad = 1.5;
  g.ring_id = "wing1_corridor";
  g.edge_index = 59;
  g.collisions = 2;
  g.forward_in_ring = true;
  msgs::GroundTruth m = ToIdl(g);
  const auto back = FromIdl(m);
  ASSERT_TRUE(back.value) << back.reason;
  EXPECT_EQ(back.value->ring_id, "wing1_corridor");
  EXPECT_EQ(back.value->edge_index, 59);
  EXPECT_EQ(back.value->collisions, 2);
  EXPECT_TRUE(back.value->forward_in_ring);
  EXPECT_DOUBLE_EQ(back.value->y_in, -3.0);
  m.pose().heading_rad(std::numeric_limits<double>::infinity());
  EXPECT_EQ(FromIdl(m).reason, "a non-finite true pose");
}

}  // namespace
}  // namespace stickrep::convert
