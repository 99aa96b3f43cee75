#include "locomotion/hallway_follower.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/units.h"
#include "locomotion/fake_sonar.h"

namespace stickrep::locomotion {
namespace {

using ::testing::DoubleNear;
using fake::Hallway;
using fake::Scan;
using fake::Segment;

TEST(HallwayFollowerTest, SensorBearingsFollowTheCameraConvention) {
  HallwayFollowerConfig c;
  EXPECT_NEAR(SensorBearingRad(0, c), kPi / 2.0, 1e-12);  // coaxial: the camera, left
  EXPECT_NEAR(SensorBearingRad(6, c), 0.0, 1e-12);        // forward
  EXPECT_NEAR(SensorBearingRad(12, c), -kPi / 2.0, 1e-12);
  EXPECT_NEAR(std::abs(SensorBearingRad(18, c)), kPi, 1e-12);  // backward
}

TEST(HallwayFollowerTest, CentredAlignedRobotSeesTheAxis) {
  const HallwayEstimate e = EstimateHallway(Scan(Hallway(), 0, 0, 0), {});
  ASSERT_TRUE(e.offset_valid);
  ASSERT_TRUE(e.heading_valid);
  EXPECT_NEAR(e.lateral_offset_in, 0.0, 0.5);
  EXPECT_NEAR(e.heading_error_rad, 0.0, DegToRad(0.5));
  EXPECT_NEAR(e.hallway_width_in, 96.0, 1.0);
  EXPECT_FALSE(e.left_open);
  EXPECT_FALSE(e.right_open);
}

TEST(HallwayFollowerTest, OffsetAndHeadingAreRecoveredBothWays) {
  for (double y : {-10.0, 10.0}) {
    for (double psi_deg : {-10.0, -5.0, 5.0, 10.0}) {
      const HallwayEstimate e = EstimateHallway(Scan(Hallway(), 0, y, DegToRad(psi_deg)), {});
      ASSERT_TRUE(e.offset_valid) << y << " " << psi_deg;
      ASSERT_TRUE(e.heading_valid) << y << " " << psi_deg;
      EXPECT_NEAR(e.lateral_offset_in, y, 1.0) << psi_deg;
      EXPECT_NEAR(e.heading_error_rad, DegToRad(psi_deg), DegToRad(1.0)) << y;
    }
  }
}

TEST(HallwayFollowerTest, DoorRecessBesideTheRobotDoesNotMoveTheWall) {
  // A 36 in door set 8 in back into the left wall, right beside the robot.
  std::vector<Segment> walls = {{{-1000, 48}, {-18, 48}}, {{-18, 48}, {-18, 56}},
                                {{-18, 56}, {18, 56}},    {{18, 56}, {18, 48}},
                                {{18, 48}, {1000, 48}},   {{-1000, -48}, {1000, -48}}};
  const HallwayEstimate e = EstimateHallway(Scan(walls, 0, 6, DegToRad(3)), {});
  ASSERT_TRUE(e.offset_valid);
  EXPECT_NEAR(e.lateral_offset_in, 6.0, 1.5);
  EXPECT_NEAR(e.left.distance_in, 42.0, 2.0);
  EXPECT_FALSE(e.left_open);
}

TEST(HallwayFollowerTest, OnlyNearNormalReadingsStillGiveTheOffset) {
  // What the footprint gate leaves: readings within 15° of the wall normal.
  HallwayFollowerConfig c;
  std::vector<SonarRange> scan = Scan(Hallway(), 0, 8, DegToRad(4));
  for (int k = 0; k < c.sensor_count; ++k) {
    const double b = SensorBearingRad(k, c) + DegToRad(4);
    const double off = std::min(std::abs(std::remainder(b - kPi / 2, 2 * kPi)),
                                std::abs(std::remainder(b + kPi / 2, 2 * kPi)));
    if (off > DegToRad(15.0)) scan[k].valid = false;
  }
  const HallwayEstimate e = EstimateHallway(scan, c);
  ASSERT_TRUE(e.offset_valid);
  EXPECT_NEAR(e.lateral_offset_in, 8.0, 1.0);
}

TEST(HallwayFollowerTest, WrongSizedScanGivesNoEstimate) {
  const HallwayEstimate e = EstimateHallway(std::vector<SonarRange>(5), {});
  EXPECT_FALSE(e.offset_valid);
  EXPECT_FALSE(e.heading_valid);
  EXPECT_EQ(e.valid_readings, 0);
}

TEST(HallwayFollowerTest, ObstacleAheadIsMeasuredAndSideWallsAreNot) {
  std::vector<Segment> walls = Hallway();
  const HallwayEstimate clear = EstimateHallway(Scan(walls, 0, 5, DegToRad(3)), {});
  EXPECT_TRUE(std::isinf(clear.free_forward_in)) << clear.free_forward_in;
  EXPECT_TRUE(std::isinf(clear.free_backward_in)) << clear.free_backward_in;
  walls.push_back({{40, -6}, {40, 6}});  // a person-sized obstacle 40 in ahead
  const HallwayEstimate e = EstimateHallway(Scan(walls, 0, 0, 0), {});
  EXPECT_NEAR(e.free_forward_in, 40.0, 3.0);
  EXPECT_TRUE(std::isinf(e.free_backward_in));
  walls.push_back({{-30, -6}, {-30, 6}});  // and one behind
  EXPECT_NEAR(EstimateHallway(Scan(walls, 0, 0, 0), {}).free_backward_in, 30.0, 3.0);
}

TEST(HallwayFollowerTest, HallwayEndAheadRequestsReversal) {
  std::vector<Segment> walls = {
      {{-1000, 48}, {60, 48}}, {{-1000, -48}, {60, -48}}, {{60, -48}, {60, 48}}};
  const HallwayEstimate e = EstimateHallway(Scan(walls, 0, 0, 0), {});
  EXPECT_NEAR(e.wall_forward_in, 60.0, 3.0);
  const TurnRequest t = DetectTurn(e, +1, {});
  EXPECT_EQ(t.kind, TurnKind::kHallwayEnd);
  // Travelling backward the end wall is behind: nothing to do.
  EXPECT_EQ(DetectTurn(e, -1, {}).kind, TurnKind::kNone);
}

// A scan with every sensor answering at 40 in but those whose bearing from the travel
// direction lies in [from_deg, to_deg], which return no echo.
std::vector<SonarRange> SilentBetween(double from_deg, double to_deg, int travel_sign) {
  const HallwayFollowerConfig c;
  std::vector<SonarRange> scan(c.sensor_count);
  for (int k = 0; k < c.sensor_count; ++k) {
    const double rel = RadToDeg(std::remainder(
        SensorBearingRad(k, c) - (travel_sign > 0 ? 0.0 : kPi), 2.0 * kPi));
    const bool silent = rel >= from_deg - 1e-6 && rel <= to_deg + 1e-6;
    scan[k] = {silent ? 0.0 : 40.0, !silent};
  }
  return scan;
}

TEST(HallwayFollowerTest, AnEmptySectorAheadOfAbeamIsABendNotAnEnd) {
  const HallwayFollowerConfig c;
  // The sonar at a 60 deg bend, seen from its far wing (science_hall_2f): silent from 15 to
  // 90 deg toward the turn, the outer wall answering on the other side.
  auto turn = EmptySectorTurnRad(SilentBetween(15, 90, +1), +1, c);
  ASSERT_TRUE(turn.has_value());
  EXPECT_NEAR(RadToDeg(*turn), 52.5, 1e-6);
  turn = EmptySectorTurnRad(SilentBetween(-90, -15, +1), +1, c);
  ASSERT_TRUE(turn.has_value());
  EXPECT_NEAR(RadToDeg(*turn), -52.5, 1e-6);
  // Travelling backward, bearings count from the backward direction.
  turn = EmptySectorTurnRad(SilentBetween(15, 90, -1), -1, c);
  ASSERT_TRUE(turn.has_value());
  EXPECT_NEAR(RadToDeg(*turn), 52.5, 1e-6);
  // The teaching building's science wing, its 60 deg turn seen travelling backward from the
  // far leg: silent from 15 to 60 deg toward the turn, the sensor at 75 deg looking straight
  // up the next stretch at a wall 132 in off, 90 and 105 deg silent again. A far echo is no
  // wall beside the base: the sector is empty to 105 deg.
  std::vector<SonarRange> far = SilentBetween(15, 105, -1);
  for (int k = 0; k < c.sensor_count; ++k) {
    const double rel = RadToDeg(std::remainder(SensorBearingRad(k, c) - kPi, 2.0 * kPi));
    if (std::abs(rel - 75.0) < 1e-6) far[k] = {132.0, true};
  }
  turn = EmptySectorTurnRad(far, -1, c);
  ASSERT_TRUE(turn.has_value());
  EXPECT_NEAR(RadToDeg(*turn), 60.0, 1e-6);
  // Within the side range that echo is a wall beside the base: the empty run stops at 60.
  for (SonarRange& r : far) {
    if (r.valid && r.range_in > 100.0) r.range_in = 60.0;
  }
  EXPECT_FALSE(EmptySectorTurnRad(far, -1, c).has_value());
  // A real end answers ahead; an open door empties two or three sensors, not five; an
  // empty sector that does not start next to the axis is no bend ahead.
  EXPECT_FALSE(EmptySectorTurnRad(SilentBetween(200, 200, +1), +1, c).has_value());
  EXPECT_FALSE(EmptySectorTurnRad(SilentBetween(30, 60, +1), +1, c).has_value());
  EXPECT_FALSE(EmptySectorTurnRad(SilentBetween(30, 105, +1), +1, c).has_value());
  // Stopped in the outer corner of the science wing's 60 deg bend, 27 in off its outer
  // wall: the left silent from 15 to 90 deg, and on the right only the sensors that meet the
  // walls near square answer (0, -15, -60, -75 deg; -30, -45 and -90 graze them).
  std::vector<SonarRange> corner = SilentBetween(15, 90, +1);
  for (int k = 0; k < c.sensor_count; ++k) {
    const double rel = RadToDeg(std::remainder(SensorBearingRad(k, c), 2.0 * kPi));
    for (const double grazing : {-30.0, -45.0, -90.0}) {
      if (std::abs(rel - grazing) < 1e-6) corner[k] = SonarRange{};
    }
  }
  turn = EmptySectorTurnRad(corner, +1, c);
  ASSERT_TRUE(turn.has_value());
  EXPECT_NEAR(RadToDeg(*turn), 52.5, 1e-6);
  // Both sides silent: an open hall, not a bend.
  std::vector<SonarRange> open(c.sensor_count);
  EXPECT_FALSE(EmptySectorTurnRad(open, +1, c).has_value());
  // A wrong-sized scan.
  EXPECT_FALSE(EmptySectorTurnRad(std::vector<SonarRange>(3), +1, c).has_value());
}

TEST(HallwayFollowerTest, LeftCornerRequestsACounterClockwiseTurn) {
  // The hallway turns left: the left wall stops at x = -36, the new hallway runs along +y
  // between x = -36 and x = 60, and the far wall at x = 60 continues to the left.
  std::vector<Segment> walls = {{{-1000, 48}, {-36, 48}},
                                {{-36, 48}, {-36, 1000}},
                                {{-1000, -48}, {60, -48}},
                                {{60, -48}, {60, 1000}}};
  // The base stands in the crossing, centred in the new hallway, its end wall 48 in ahead.
  const HallwayEstimate e = EstimateHallway(Scan(walls, 12, 0, 0), {});
  EXPECT_TRUE(e.left_open);
  EXPECT_FALSE(e.right_open);
  const TurnRequest t = DetectTurn(e, +1, {});
  EXPECT_EQ(t.kind, TurnKind::kCorner);
  EXPECT_NEAR(t.rotate_rad, kPi / 2.0, 1e-12);
  // Far from the corner nothing is requested.
  EXPECT_EQ(DetectTurn(EstimateHallway(Scan(walls, -200, 0, 0), {}), +1, {}).kind, TurnKind::kNone);
}

// A 96 in hallway along +x that bends left by `bend` at x = 0: the outer (right) wall turns
// there, the inner wall 96 tan(bend / 2) earlier.
std::vector<Segment> BendLeft(double bend) {
  const double w = 96.0;
  const double dx = std::cos(bend) * 1000.0, dy = std::sin(bend) * 1000.0;
  const double inner_x = -w * std::tan(bend / 2.0);
  return {{{-1000, -w / 2}, {0, -w / 2}},
          {{0, -w / 2}, {dx, -w / 2 + dy}},
          {{-1000, w / 2}, {inner_x, w / 2}},
          {{inner_x, w / 2}, {inner_x + dx, w / 2 + dy}}};
}

TEST(HallwayFollowerTest, ObliqueWallAheadIsMeasuredAtItsOwnAngle) {
  // A reading fits every plane whose normal lies in its 23.6 deg cone: the angle is the
  // middle of the angles the sensors agree on, not the first of them.
  for (const double bend_deg : {30.0, 45.0, 60.0}) {
    const std::vector<Segment> walls = BendLeft(DegToRad(bend_deg));
    int seen = 0;
    for (double x = -80.0; x <= -10.0; x += 10.0) {
      const HallwayEstimate e = EstimateHallway(Scan(walls, x, 0, 0), {});
      if (!std::isfinite(e.wall_forward_in) || e.wall_forward_normal_rad == 0.0) continue;
      ++seen;
      EXPECT_NEAR(RadToDeg(e.wall_forward_normal_rad), -(90.0 - bend_deg), 6.0)
          << "bend " << bend_deg << " deg, base at x = " << x;
    }
    EXPECT_GE(seen, 2) << "bend " << bend_deg << " deg";
  }
}

TEST(HallwayFollowerTest, SideWallHeadedIntoAtASteepAngleBoundsTheFreeSpace) {
  const std::vector<Segment> walls = Hallway(48.0);  // 96 in wide
  // 18 in from the right wall, heading 25 deg into it: the travel line meets it (less the
  // base's radius) about 25 in ahead, though every echo from it fits the side wall and no
  // front sensor hears it.
  const HallwayEstimate into = EstimateHallway(Scan(walls, 0, -30, DegToRad(-25.0)), {});
  ASSERT_TRUE(into.right.valid);
  EXPECT_LT(into.free_forward_in, 40.0);
  // Parallel to it, or within the steering's few degrees, the way is clear.
  EXPECT_TRUE(std::isinf(EstimateHallway(Scan(walls, 0, -30, 0.0), {}).free_forward_in));
  EXPECT_TRUE(std::isinf(
      EstimateHallway(Scan(walls, 0, -30, DegToRad(-5.0)), {}).free_forward_in));
}

TEST(HallwayFollowerTest, AnEchoOffTheFrontFanInTheSweptPathStopsTheBase) {
  // A post 19 in ahead, 10.5-11.5 in left of the travel line: 29-31 deg off the travel
  // direction, outside every front sensor's cone (15 + 11.8 deg at most), inside the 30 deg
  // sensor's. The base (7.5 in radius) passing it would clear it by 3-4 in only.
  std::vector<Segment> walls = Hallway();
  walls.push_back({{19, 10.5}, {19, 11.5}});
  const HallwayEstimate in_path = EstimateHallway(Scan(walls, 0, 0, 0), {});
  EXPECT_LE(in_path.free_forward_in, HallwayFollowerConfig{}.stop_distance_in);
  HallwayFollower follower;
  const SteerCommand cmd = follower.Steer(in_path, 1.0, 0.05);
  EXPECT_TRUE(cmd.stopped_for_obstacle);
  EXPECT_EQ(cmd.linear_ftps, 0.0);
  // The same post 20 in left of the travel line is passed.
  walls.back() = {{34, 19.5}, {34, 20.5}};
  EXPECT_TRUE(std::isinf(EstimateHallway(Scan(walls, 0, 0, 0), {}).free_forward_in));
  // A post 14 in left of it: the 30 deg sensor's cone cannot tell it from one 9 in left,
  // within the radius plus the 4 in of clearance (the base slows for it) but outside the
  // radius alone.
  walls.back() = {{24, 13.5}, {24, 14.5}};
  EXPECT_TRUE(std::isfinite(EstimateHallway(Scan(walls, 0, 0, 0), {}).free_forward_in));
  HallwayFollowerConfig bare;
  bare.swept_clearance_in = 0.0;
  EXPECT_TRUE(std::isinf(EstimateHallway(Scan(walls, 0, 0, 0, bare), bare).free_forward_in));
}

TEST(HallwayFollowerTest, CornerTravellingBackwardTurnsTheOtherWay) {
  HallwayEstimate e;
  e.wall_backward_in = 50.0;
  e.left_open = true;
  const TurnRequest t = DetectTurn(e, -1, {});
  EXPECT_EQ(t.kind, TurnKind::kCorner);
  EXPECT_NEAR(t.rotate_rad, -kPi / 2.0, 1e-12);
}

TEST(HallwayFollowerTest, SpeedIsCappedAtTheRatedSpeed) {
  HallwayFollower f;
  HallwayEstimate e;  // clear way, no walls
  SteerCommand cmd;
  for (int i = 0; i < 100; ++i) cmd = f.Steer(e, 5.0, 0.1);
  EXPECT_DOUBLE_EQ(cmd.linear_ftps, 2.6);
  EXPECT_DOUBLE_EQ(cmd.angular_radps, 0.0);
  for (int i = 0; i < 100; ++i) cmd = f.Steer(e, -5.0, 0.1);
  EXPECT_DOUBLE_EQ(cmd.linear_ftps, -2.6);
}

TEST(HallwayFollowerTest, SpeedUpIsRampedAndNonFiniteInputStops) {
  HallwayFollower f;
  HallwayEstimate e;
  EXPECT_NEAR(f.Steer(e, 2.6, 0.1).linear_ftps, 0.15, 1e-12);
  EXPECT_NEAR(f.Steer(e, 2.6, 0.1).linear_ftps, 0.30, 1e-12);
  EXPECT_DOUBLE_EQ(f.Steer(e, std::nan(""), 0.1).linear_ftps, 0.0);
}

TEST(HallwayFollowerTest, RampsDownAndStopsBeforeAnObstacle) {
  HallwayFollowerConfig c;
  HallwayFollower f(c);
  HallwayEstimate e;
  for (int i = 0; i < 40; ++i) f.Steer(e, 2.6, 0.1);
  // Drive at an obstacle 120 in ahead; it comes nearer as the base moves.
  double obstacle_in = 120.0;
  double previous = f.last_speed_ftps();
  bool stopped = false;
  for (int i = 0; i < 200 && !stopped; ++i) {
    e.free_forward_in = obstacle_in;
    const SteerCommand cmd = f.Steer(e, 2.6, 0.05);
    EXPECT_LE(cmd.linear_ftps, previous + 1e-12);
    previous = cmd.linear_ftps;
    obstacle_in -= FeetToInches(cmd.linear_ftps) * 0.05;
    stopped = cmd.stopped_for_obstacle || cmd.linear_ftps == 0.0;
  }
  EXPECT_TRUE(stopped);
  EXPECT_GE(obstacle_in, c.stop_distance_in - 2.0);
  EXPECT_LE(obstacle_in, c.stop_distance_in + 6.0);
  e.free_forward_in = c.stop_distance_in - 1.0;
  const SteerCommand held = f.Steer(e, 2.6, 0.05);
  EXPECT_DOUBLE_EQ(held.linear_ftps, 0.0);
  EXPECT_TRUE(held.stopped_for_obstacle);
  // Backing away from it is allowed.
  EXPECT_LT(f.Steer(e, -2.6, 0.05).linear_ftps, 0.0);
}

// A unicycle in the hallway frame driven by the follower for 60 s at full speed, from
// `y0_in` off the axis and `psi0_deg` heading error. The estimate is the true state.
struct Trace {
  double final_y_in = 0.0, final_psi_rad = 0.0;
  double overshoot_in = 0.0;  // farthest excursion past the axis on the other side
  int axis_crossings = 0;
  double max_abs_psi_after_settle_rad = 0.0;
};

Trace Simulate(double y0_in, double psi0_deg, double speed_ftps) {
  HallwayFollower f;
  const double dt = 0.05;
  double y = y0_in, psi = DegToRad(psi0_deg);
  Trace t;
  double last_y = y;
  for (int i = 0; i < static_cast<int>(60.0 / dt); ++i) {
    HallwayEstimate e;
    e.offset_valid = e.heading_valid = true;
    e.lateral_offset_in = y;
    e.heading_error_rad = psi;
    const SteerCommand cmd = f.Steer(e, speed_ftps, dt);
    y += FeetToInches(cmd.linear_ftps) * std::sin(psi) * dt;
    psi += cmd.angular_radps * dt;
    if ((y > 0) != (last_y > 0) && y != 0.0) ++t.axis_crossings;
    if (y0_in * y < 0.0) t.overshoot_in = std::max(t.overshoot_in, std::abs(y));
    if (i * dt > 20.0)
      t.max_abs_psi_after_settle_rad = std::max(t.max_abs_psi_after_settle_rad, std::abs(psi));
    last_y = y;
  }
  t.final_y_in = y;
  t.final_psi_rad = psi;
  return t;
}

TEST(HallwayFollowerTest, ConvergesIntoTheEnvelopeWithoutOscillating) {
  // 10 in off the axis with 10° heading error, toward and away from the axis, forward and
  // backward travel. Stated bound: overshoot past the axis below 1 in (10 % of the initial
  // offset), at most one crossing, inside 1 in / 1° after 60 s (envelope: 12 in / 7.5°).
  for (double speed : {2.6, -2.6}) {
    for (double psi0 : {-10.0, 10.0}) {
      const Trace t = Simulate(10.0, psi0, speed);
      SCOPED_TRACE(::testing::Message() << "speed " << speed << " psi0 " << psi0);
      EXPECT_LT(std::abs(t.final_y_in), 1.0);
      EXPECT_LT(std::abs(t.final_psi_rad), DegToRad(1.0));
      EXPECT_LT(t.overshoot_in, 1.0);
      EXPECT_LE(t.axis_crossings, 1);
      EXPECT_LT(t.max_abs_psi_after_settle_rad, DegToRad(7.5));
    }
  }
}

TEST(HallwayFollowerTest, ClosedLoopThroughTheScanStaysInTheEnvelope) {
  // The whole chain: simulated scans, the estimator, the controller, a unicycle.
  HallwayFollower f;
  const std::vector<Segment> walls = Hallway();
  const double dt = 0.1;
  double x = -900.0, y = 10.0, psi = DegToRad(10.0);
  double worst_late_y = 0.0, worst_late_psi = 0.0;
  for (int i = 0; i < 400; ++i) {  // 40 s, about 100 ft
    const SteerCommand cmd = f.Steer(EstimateHallway(Scan(walls, x, y, psi), {}), 2.6, dt);
    const double v_inps = FeetToInches(cmd.linear_ftps);
    x += v_inps * std::cos(psi) * dt;
    y += v_inps * std::sin(psi) * dt;
    psi += cmd.angular_radps * dt;
    if (i * dt > 15.0) {
      worst_late_y = std::max(worst_late_y, std::abs(y));
      worst_late_psi = std::max(worst_late_psi, std::abs(psi));
    }
  }
  EXPECT_LT(worst_late_y, 3.0);
  EXPECT_LT(worst_late_psi, DegToRad(3.0));
}

TEST(HallwayFollowerTest, RejectsBadConfig) {
  HallwayFollowerConfig c;
  c.length_scale_in = 0.0;
  EXPECT_THROW(HallwayFollower{c}, std::invalid_argument);
  HallwayFollowerConfig d;
  d.swept_clearance_in = -1.0;
  EXPECT_THROW(HallwayFollower{d}, std::invalid_argument);
}

}  // namespace
}  // namespace stickrep::locomotion
