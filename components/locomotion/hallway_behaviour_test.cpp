#include "locomotion/hallway_behaviour.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "common/units.h"
#include "locomotion/fake_sonar.h"

namespace stickrep::locomotion {
namespace {

using fake::Scan;
using fake::Segment;

double WrapPi(double a) { return std::remainder(a, 2.0 * kPi); }

// A unicycle base among wall segments, driven by the behaviour at 20 Hz with a scan every
// 0.1 s; the odometry is exact. Frame: the hallway runs along +x with the camera's wall
// at y = +60 (a 120 in hallway), the base starts on the axis facing +x.
struct Drive {
  explicit Drive(std::vector<Segment> w, HallwayBehaviourConfig c = {}) : walls(std::move(w)), b(c) {}

  // Steps until `done` holds or `seconds` pass; returns whether `done` held.
  template <typename Done>
  bool Until(Done done, double seconds, double speed_ftps = 2.6) {
    for (int i = 0; i < static_cast<int>(seconds / kDt); ++i) {
      if (step % 2 == 0) b.OnScan(Scan(walls, x, y, psi), t);
      out = b.Step(speed_ftps, psi, odometer, t, kDt);
      max_speed = std::max(max_speed, std::abs(out.linear_ftps));
      max_rate = std::max(max_rate, std::abs(out.angular_radps));
      max_rate_change = std::max(max_rate_change, std::abs(out.angular_radps - last_rate));
      last_rate = out.angular_radps;
      turns += out.turn_started;
      reversals += out.reversed;
      obstacle_stops += out.obstacle_stop_started;
      stalls += out.stalled;
      double ds = FeetToInches(out.linear_ftps) * kDt * motion_gain;
      // A pane the sonar does not see: the base's head stops at it, the wheels with it.
      if (ds > 0.0 && x + kHeadRadiusIn + ds * std::cos(psi) > glass_x) ds = 0.0;
      x += ds * std::cos(psi + out.angular_radps * kDt / 2.0);
      y += ds * std::sin(psi + out.angular_radps * kDt / 2.0);
      psi = WrapPi(psi + out.angular_radps * kDt);
      odometer += ds;
      t += kDt;
      ++step;
      if (done()) return true;
    }
    return false;
  }

  static constexpr double kDt = 0.05;
  static constexpr double kHeadRadiusIn = 7.5;
  std::vector<Segment> walls;
  // Glass across the hallway at this x (the sonar does not see it), and the share of the
  // commanded travel the base makes (a load, a slope).
  double glass_x = std::numeric_limits<double>::infinity();
  double motion_gain = 1.0;
  HallwayBehaviour b;
  BehaviourOutput out;
  double x = -400.0, y = 0.0, psi = 0.0, odometer = 0.0, t = 0.0;
  int step = 0, turns = 0, reversals = 0, obstacle_stops = 0, stalls = 0;
  double max_speed = 0.0, max_rate = 0.0, max_rate_change = 0.0, last_rate = 0.0;
};

// The camera's wall ends at x = 0 and the hallway turns left (toward it) into a hallway
// between x = 0 and x = 120 running along +y: a convex corner of the mapped wall.
std::vector<Segment> LeftCorner() {
  return {{{-2000, 60}, {0, 60}}, {{0, 60}, {0, 2000}},
          {{-2000, -60}, {120, -60}}, {{120, -60}, {120, 2000}}};
}

// The hallway turns right: the camera's wall runs on round the corner (concave).
std::vector<Segment> RightCorner() {
  return {{{-2000, 60}, {60, 60}}, {{60, 60}, {60, -2000}},
          {{-2000, -60}, {-60, -60}}, {{-60, -60}, {-60, -2000}}};
}

TEST(HallwayBehaviourTest, HoldsTheBaseUntilAScanArrivesAndWhenScansStop) {
  HallwayBehaviour b;
  BehaviourOutput out = b.Step(2.6, 0.0, 0.0, 0.0, 0.05);
  EXPECT_EQ(out.state, BehaviourState::kNoScan);
  EXPECT_EQ(out.linear_ftps, 0.0);
  EXPECT_THAT(out.reason, ::testing::HasSubstr("first sonar scan"));
  b.OnScan(Scan(fake::Hallway(60), 0, 0, 0), 0.0);
  out = b.Step(2.6, 0.0, 0.0, 0.05, 0.05);
  EXPECT_EQ(out.state, BehaviourState::kFollowing);
  EXPECT_GT(out.linear_ftps, 0.0);
  out = b.Step(2.6, 0.0, 0.0, 0.7, 0.05);  // 0.7 s since the scan
  EXPECT_EQ(out.state, BehaviourState::kNoScan);
  EXPECT_EQ(out.linear_ftps, 0.0);
  EXPECT_THAT(out.reason, ::testing::HasSubstr("no sonar scan for 0.7 s"));
}

TEST(HallwayBehaviourTest, ReportsTheEnvelopeOnceTheTrackIsKnown) {
  // One scan gives the offset to a fraction of an inch but the heading only roughly: the
  // envelope is reported once travel has pinned the heading down.
  Drive near(fake::Hallway(60));
  near.y = 3.0;
  near.psi = DegToRad(2.0);
  near.Until([] { return true; }, 1.0);
  EXPECT_TRUE(near.out.offset_valid);
  EXPECT_NEAR(near.out.lateral_offset_in, 3.0, 1.0);
  EXPECT_FALSE(near.out.in_envelope);
  EXPECT_TRUE(near.Until([&] { return near.out.in_envelope; }, 3.0));
  EXPECT_LE(std::abs(near.out.lateral_offset_in - near.y), 1.0);
  EXPECT_LE(std::abs(RadToDeg(near.out.heading_error_rad - near.psi)), 1.0);

  Drive far(fake::Hallway(60));
  far.y = -20.0;
  far.Until([] { return true; }, 1.0);
  EXPECT_NEAR(far.out.lateral_offset_in, -20.0, 1.0);
  EXPECT_FALSE(far.out.in_envelope);
}

TEST(HallwayBehaviourTest, PacesTheBaseSoTheWidestDoorStaysWholeInViewForTheSetFrames) {
  HallwayBehaviourConfig c;
  c.frames_per_door = 3;
  // 48 in from the wall the 55.8° lens sees 50.8 in: 10.8 in to spare for a 40 in door,
  // 3.6 in a frame at 5 Hz, 18 in/s.
  EXPECT_NEAR(ViewPacedSpeedFtps(c, 48.0), InchesToFeet((2.0 * 48.0 * std::tan(DegToRad(55.817 / 2.0)) - 40.0) / 0.6), 1e-9);
  EXPECT_NEAR(ViewPacedSpeedFtps(c, 48.0), 1.50, 0.01);
  EXPECT_GT(ViewPacedSpeedFtps(c, 60.0), 2.6);          // the text's 120 in hallways: unpaced
  EXPECT_EQ(ViewPacedSpeedFtps(c, 30.0), c.min_view_speed_ftps);  // the door never fits
  c.frames_per_door = 0;
  EXPECT_TRUE(std::isinf(ViewPacedSpeedFtps(c, 48.0)));

  // Closed loop in a 96 in corridor: the base settles at the paced speed, not the 2.6 ft/s
  // commanded; in the 120 in hallway it reaches 2.6.
  c.frames_per_door = 3;
  Drive narrow(fake::Hallway(48), c);
  narrow.Until([] { return false; }, 8.0);
  EXPECT_NEAR(narrow.max_speed, ViewPacedSpeedFtps(c, 48.0), 0.05);
  Drive wide(fake::Hallway(60), c);
  wide.Until([] { return false; }, 8.0);
  EXPECT_NEAR(wide.max_speed, 2.6, 1e-9);
}

TEST(HallwayBehaviourTest, RidesOffTheAxisAwayFromTheMappedWallWhereTheHallwayIsNarrow) {
  HallwayBehaviourConfig c;
  c.frames_per_door = 3;
  c.max_view_offset_in = 10.0;
  // At 55.4 in from the wall the widest door stays in view for 3 frames at 2.6 ft/s.
  const double top_range_in = (40.0 + 3 * 0.2 * 31.2) / (2.0 * std::tan(DegToRad(55.817 / 2.0)));
  EXPECT_NEAR(ViewOffsetIn(c, 96.0), -(top_range_in - 48.0), 1e-9);
  EXPECT_DOUBLE_EQ(ViewOffsetIn(c, 88.0), -10.0);  // capped
  EXPECT_DOUBLE_EQ(ViewOffsetIn(c, 120.0), 0.0);   // the text's hallways: on the axis
  EXPECT_DOUBLE_EQ(ViewOffsetIn(c, 60.0), -6.0);   // never nearer the far wall than 24 in
  EXPECT_DOUBLE_EQ(ViewOffsetIn(c, 40.0), 0.0);
  HallwayBehaviourConfig off = c;
  off.max_view_offset_in = 0.0;
  EXPECT_DOUBLE_EQ(ViewOffsetIn(off, 88.0), 0.0);
  off = c;
  off.frames_per_door = 0;
  EXPECT_DOUBLE_EQ(ViewOffsetIn(off, 88.0), 0.0);

  // Closed loop from the axis of an 88 in corridor: after 240 in of travel the base takes
  // the corridor for narrow and settles 10 in off the axis, away from the camera's wall,
  // inside the envelope judged about that line, at the pace of 54 in from the wall (2.4
  // ft/s, not the axis's 0.96).
  Drive narrow(fake::Hallway(44), c);
  narrow.x = -950.0;
  EXPECT_TRUE(narrow.Until([&] { return narrow.odometer >= 230.0; }, 60.0));
  EXPECT_DOUBLE_EQ(narrow.out.target_offset_in, 0.0);  // not yet
  narrow.Until([] { return false; }, 25.0);
  EXPECT_NEAR(narrow.y, -10.0, 1.0);
  EXPECT_NEAR(narrow.out.lateral_offset_in, narrow.y, 1.0);
  EXPECT_DOUBLE_EQ(narrow.out.target_offset_in, -10.0);
  EXPECT_TRUE(narrow.out.in_envelope);
  EXPECT_NEAR(std::abs(narrow.out.linear_ftps), ViewPacedSpeedFtps(c, 54.0), 0.05);
  EXPECT_GT(std::abs(narrow.out.linear_ftps), 2.3);
  // With the corridor's end known ahead (from about 100 in) it steers back toward the
  // axis, and is about half-way there when it stops before the end.
  const double end_x = narrow.x + 500.0;
  narrow.walls.push_back({{end_x, -44}, {end_x, 44}});
  double off_at_in = 0.0;
  EXPECT_TRUE(narrow.Until(
      [&] {
        if (off_at_in == 0.0 && narrow.out.target_offset_in == 0.0) off_at_in = end_x - narrow.x;
        return narrow.out.reversed;
      },
      30.0));
  EXPECT_GT(off_at_in, 80.0);
  EXPECT_LT(off_at_in, 130.0);
  EXPECT_DOUBLE_EQ(narrow.out.target_offset_in, 0.0);
  EXPECT_GT(narrow.y, -7.0);
  EXPECT_NEAR(narrow.x, end_x - 44.0, 4.0);
  // Started 8 in nearer the camera's wall than the axis (slow there: 36 in from the wall)
  // it crosses to the same line.
  Drive near(fake::Hallway(44), c);
  near.x = -950.0;
  near.y = 8.0;
  EXPECT_TRUE(near.Until([&] { return near.y <= -9.0; }, 90.0)) << near.y;
  EXPECT_LE(near.x, 900.0);
  // In a 96 in corridor it stops short of the cap, where the pace allows the top speed.
  Drive mid(fake::Hallway(48), c);
  mid.x = -950.0;
  mid.Until([] { return false; }, 40.0);
  EXPECT_NEAR(mid.y, -(top_range_in - 48.0), 1.0);
  EXPECT_NEAR(std::abs(mid.out.linear_ftps), 2.6, 0.01);
  // In the 120 in hallway it keeps to the axis.
  Drive wide(fake::Hallway(60), c);
  wide.Until([] { return false; }, 20.0);
  EXPECT_NEAR(wide.y, 0.0, 0.5);
  EXPECT_DOUBLE_EQ(wide.out.target_offset_in, 0.0);
}

// A 120 in hallway whose camera wall juts out 20 in from x = 0 to x = `length_in`.
std::vector<Segment> JutHallway(double length_in) {
  return {{{-1000, 60}, {0, 60}},        {{0, 60}, {0, 40}},
          {{0, 40}, {length_in, 40}},    {{length_in, 40}, {length_in, 60}},
          {{length_in, 60}, {1000, 60}}, {{-1000, -60}, {1000, -60}}};
}

TEST(HallwayBehaviourTest, AWallThatJutsOutForAFewFeetOrAnAlcoveLeavesTheLineAsItWas) {
  HallwayBehaviourConfig c;
  c.frames_per_door = 3;
  c.max_view_offset_in = 10.0;
  // A 120 in hallway whose camera wall juts out 20 in for 120 in of its length: 100 in
  // there, narrow, but for less than the 240 in of travel the state asks for.
  Drive jut(JutHallway(120.0), c);
  double most_off = 0.0;
  EXPECT_TRUE(jut.Until(
      [&] {
        most_off = std::max(most_off, std::abs(jut.out.target_offset_in));
        return jut.x > 400.0;
      },
      60.0));
  EXPECT_EQ(most_off, 0.0);
  // The same jut 600 in long is a narrow stretch: the line moves off the axis once the
  // base has travelled 240 in along it (the side sensors see the jut from a few inches
  // before its face).
  Drive long_jut(JutHallway(600.0), c);
  double first_off_x = 0.0;
  EXPECT_TRUE(long_jut.Until(
      [&] {
        first_off_x = long_jut.x;
        return long_jut.out.target_offset_in < 0.0;
      },
      60.0));
  EXPECT_GT(first_off_x, 220.0);
  EXPECT_LT(first_off_x, 300.0);
  // In an 88 in corridor taken for narrow, a 72 in alcove 40 in deep on the camera's side
  // keeps the line where it was.
  std::vector<Segment> alcove = {{{-1000, 44}, {0, 44}}, {{0, 44}, {0, 84}},
                                 {{0, 84}, {72, 84}},    {{72, 84}, {72, 44}},
                                 {{72, 44}, {1000, 44}}, {{-1000, -44}, {1000, -44}}};
  Drive past(alcove, c);
  past.x = -900.0;
  EXPECT_TRUE(past.Until([&] { return past.out.target_offset_in < 0.0; }, 60.0));
  EXPECT_LT(past.x, -200.0);
  double least_off = 10.0;
  EXPECT_TRUE(past.Until(
      [&] {
        least_off = std::min(least_off, std::abs(past.out.target_offset_in));
        return past.x > 300.0;
      },
      60.0));
  EXPECT_EQ(least_off, 10.0);
}

// An 88 in corridor whose camera wall has a door alcove 40 in deep and 72 in long at
// x = 0..72; with `open_right`, the other side opens into a hall from x = -300 to 300.
std::vector<Segment> AlcoveCorridor(bool open_right) {
  std::vector<Segment> w = {{{-1000, 44}, {0, 44}},  {{0, 44}, {0, 84}},     {{0, 84}, {72, 84}},
                            {{72, 84}, {72, 44}},    {{72, 44}, {1000, 44}}};
  if (open_right) {
    w.push_back({{-1000, -44}, {-300, -44}});
    w.push_back({{300, -44}, {1000, -44}});
  } else {
    w.push_back({{-1000, -44}, {1000, -44}});
  }
  return w;
}

TEST(HallwayBehaviourTest, PassesADeepAlcoveOnTheTrackAtASlowPace) {
  // At 0.9 ft/s (the camera pacing of an 88 in corridor) the alcove lasts 6.7 s of scans:
  // it is a recess in the wall, not a wall that moved, with the other wall in range or not.
  for (const bool open_right : {false, true}) {
    SCOPED_TRACE(open_right ? "the other side open" : "both walls");
    Drive r(AlcoveCorridor(open_right));
    double max_y = 0.0;
    ASSERT_TRUE(r.Until(
        [&] {
          if (r.x > -200.0) max_y = std::max(max_y, std::abs(r.y));
          return r.x > 200.0;
        },
        120.0, 0.9));
    // Half the envelope's 12 in (a fit across the alcove's edge still pulls a little).
    EXPECT_LE(max_y, 6.0);
    EXPECT_EQ(r.reversals + r.turns, 0);
  }
}

// A track at offset `y0`, heading 0, certain of both after a few plain scans.
HallwayTracker SettledTrack(double y0) {
  HallwayTracker t;
  for (int i = 0; i < 40; ++i) {
    t.Predict(1.0, 0.0);
    t.UpdateOffset(y0);
  }
  return t;
}

TEST(HallwayTrackerTest, ARecessOfSteadyDepthIsHeldOffForItsLength) {
  // The camera's wall steps 24 in back for 90 in: every reading puts the base 24 in
  // farther from it than the track does, with noise. None moves the track.
  HallwayTracker t = SettledTrack(0.0);
  for (int i = 0; i < 90; ++i) {
    t.Predict(1.0, 0.0);
    const double noise = (i % 3 - 1) * 0.8;
    EXPECT_FALSE(t.UpdateOffset(-24.0 + noise, /*recess=*/true)) << "at " << i << " in";
  }
  EXPECT_NEAR(t.offset_in(), 0.0, 0.5);
  // Back on the wall the track carries on.
  t.Predict(1.0, 0.0);
  EXPECT_TRUE(t.UpdateOffset(0.2));
}

TEST(HallwayTrackerTest, ReadingsThatKeepDriftingFartherRestartTheTrackEarly) {
  // The track believes the base parallel to the wall, 20 in nearer it than the axis; the
  // base really is on the axis and turned 20 degrees away from the wall, so each reading
  // puts it farther out than the last: no recess has such a back. The track restarts at
  // twice the drift window, not after the 96 in a recess is held.
  HallwayTracker t = SettledTrack(20.0);
  const double slope = std::tan(DegToRad(20.0));
  double restarted_at = -1.0;
  for (int i = 1; i <= 96 && restarted_at < 0.0; ++i) {
    t.Predict(1.0, 0.0);
    if (t.UpdateOffset(-slope * i, /*recess=*/true)) restarted_at = i;
  }
  EXPECT_GE(restarted_at, 2.0 * HallwayTrackerNoise{}.recess_window_in);
  EXPECT_LE(restarted_at, 2.0 * HallwayTrackerNoise{}.recess_window_in + 2.0);
  EXPECT_NEAR(t.offset_in(), -slope * restarted_at, 1e-9);
}

TEST(HallwayTrackerTest, AScanThatRestartsTheTrackRestartsItsHeadingToo) {
  // The base entered a new stretch round a 40 deg bend: the track holds the last stretch
  // (on the axis, heading 0), the scans read the base 20 in off the new axis and turned
  // 40 deg to it. Once they restart the track it starts from their heading, with the
  // uncertainty of a start and of one scan's fit, not from 0.
  HallwayTracker t = SettledTrack(0.0);
  const HallwayTrackerNoise noise;
  const double h = DegToRad(40.0);
  int restarted = 0;
  for (int i = 1; i <= noise.reinit_after && restarted == 0; ++i) {
    t.Predict(1.0, 0.0);
    if (t.UpdateScan(20.0 + i * std::sin(h), h)) restarted = i;
  }
  ASSERT_EQ(restarted, noise.reinit_after);
  const double p0 = std::pow(noise.initial_heading_sigma_deg, 2);
  const double r = std::pow(noise.heading_sigma_deg, 2);
  EXPECT_NEAR(t.heading_rad(), h * p0 / (p0 + r), 1e-9);
  EXPECT_FALSE(t.heading_known());
  // The next scans, and the offsets' own slope, settle it on the new stretch.
  for (int i = 1; i <= 30; ++i) {
    t.Predict(1.0, 0.0);
    t.UpdateScan(20.0 + (noise.reinit_after + i) * std::sin(h), h);
  }
  EXPECT_TRUE(t.heading_known());
  EXPECT_NEAR(t.heading_rad(), h, DegToRad(1.0));
  // A scan with no heading fit restarts the track at heading 0 as before.
  HallwayTracker u = SettledTrack(0.0);
  for (int i = 1; i <= noise.reinit_after; ++i) {
    u.Predict(1.0, 0.0);
    u.UpdateScan(20.0, std::numeric_limits<double>::quiet_NaN());
  }
  EXPECT_DOUBLE_EQ(u.heading_rad(), 0.0);
  EXPECT_DOUBLE_EQ(u.offset_in(), 20.0);
}

TEST(HallwayBehaviourTest, TurnsLeftAtAConvexCornerOntoTheNewAxis) {
  Drive r(LeftCorner());
  // Done once it has gone 10 ft up the new hallway.
  ASSERT_TRUE(r.Until([&] { return r.y > 120.0; }, 60.0)) << r.out.reason;
  EXPECT_EQ(r.turns, 1);
  EXPECT_NEAR(r.x, 60.0, 4.0);  // stopped on the new hallway's axis before turning
  EXPECT_NEAR(r.psi, kPi / 2.0, DegToRad(3.0));
  ASSERT_TRUE(r.Until([&] { return r.y > 600.0; }, 60.0));
  EXPECT_NEAR(r.x, 60.0, 3.0);
  EXPECT_LE(r.max_speed, 2.6);
}

TEST(HallwayBehaviourTest, TurnsRightAtAConcaveCornerKeepingTheWallOnTheLeft) {
  Drive r(RightCorner());
  ASSERT_TRUE(r.Until([&] { return r.y < -120.0; }, 60.0)) << r.out.reason;
  EXPECT_EQ(r.turns, 1);
  EXPECT_NEAR(r.x, 0.0, 4.0);
  EXPECT_NEAR(r.psi, -kPi / 2.0, DegToRad(3.0));
}

TEST(HallwayBehaviourTest, TurnsInPlaceWithARampedLimitedRate) {
  HallwayBehaviourConfig c;
  Drive r(RightCorner(), c);
  ASSERT_TRUE(r.Until([&] { return r.out.state == BehaviourState::kTurning; }, 60.0));
  const double x0 = r.x, y0 = r.y, psi0 = r.psi;
  double moved = 0.0, max_rate = 0.0, max_change = 0.0, previous = 0.0, last = 0.0;
  ASSERT_TRUE(r.Until(
      [&] {
        if (r.out.state != BehaviourState::kTurning) return true;
        moved = std::max(moved, std::hypot(r.x - x0, r.y - y0));
        max_rate = std::max(max_rate, std::abs(r.out.angular_radps));
        max_change = std::max(max_change, std::abs(r.out.angular_radps - previous));
        previous = last = r.out.angular_radps;
        return false;
      },
      20.0));
  EXPECT_EQ(moved, 0.0);  // in place: no linear speed while turning
  EXPECT_NEAR(max_rate, c.turn_rate_radps, 1e-9);
  EXPECT_LE(max_change, c.turn_accel_radps2 * Drive::kDt + 1e-9);
  // The rate is ramped down to the end: the last step within the tolerance's braking rate.
  EXPECT_LE(std::abs(last), std::sqrt(2.0 * c.turn_accel_radps2 * DegToRad(2.0 * c.turn_tolerance_deg)));
  EXPECT_NEAR(WrapPi(r.psi - psi0), -kPi / 2.0, DegToRad(c.turn_tolerance_deg + 0.5));
}

TEST(HallwayBehaviourTest, ReversesAtAHallwayEnd) {
  Drive r({{{-2000, 60}, {0, 60}}, {{0, 60}, {0, -60}}, {{-2000, -60}, {0, -60}}});
  ASSERT_TRUE(r.Until([&] { return r.reversals > 0; }, 60.0)) << r.out.reason;
  EXPECT_NEAR(r.x, -60.0, 4.0);
  EXPECT_EQ(r.out.travel_sign, -1);
  EXPECT_THAT(r.out.reason, ::testing::HasSubstr("travel reversed"));
  const double x_at_end = r.x;
  ASSERT_TRUE(r.Until([&] { return r.x < x_at_end - 120.0; }, 30.0));
  EXPECT_EQ(r.turns, 0);
  EXPECT_NEAR(r.psi, 0.0, DegToRad(3.0));  // backward, still facing the same way
}

// A 96 in hallway along +x that bends by `bend_deg` to the left (toward the camera's wall)
// at x = 0: the walls meet at 180 - bend on the inside and 180 + bend outside.
std::vector<Segment> Bend(double bend_deg) {
  const double h = 48.0, a = DegToRad(bend_deg);
  const double inner = -h * std::tan(a / 2.0), outer = h * std::tan(a / 2.0);
  const double dx = 2000 * std::cos(a), dy = 2000 * std::sin(a);
  return {{{-2000, h}, {inner, h}}, {{inner, h}, {inner + dx, h + dy}},
          {{-2000, -h}, {outer, -h}}, {{outer, -h}, {outer + dx, -h + dy}}};
}

double Clearance(const std::vector<Segment>& walls, double x, double y) {
  double best = 1e9;
  for (const Segment& s : walls) {
    const double ex = s.b.x - s.a.x, ey = s.b.y - s.a.y;
    const double t =
        std::clamp(((x - s.a.x) * ex + (y - s.a.y) * ey) / (ex * ex + ey * ey), 0.0, 1.0);
    best = std::min(best, std::hypot(x - (s.a.x + t * ex), y - (s.a.y + t * ey)));
  }
  return best;
}

TEST(HallwayBehaviourTest, TurnsAtCornersThatAreNotSquareByWhatTheHallwayTurns) {
  for (double bend : {45.0, 60.0}) {
    Drive r(Bend(bend));
    double closest = 1e9;
    const double ux = std::cos(DegToRad(bend)), uy = std::sin(DegToRad(bend));
    // 20 ft down the new stretch, along its axis.
    ASSERT_TRUE(r.Until(
        [&] {
          closest = std::min(closest, Clearance(r.walls, r.x, r.y));
          return r.x * ux + r.y * uy > 240.0;
        },
        90.0))
        << bend << " deg: " << r.out.reason;
    EXPECT_EQ(r.turns, 1) << bend;
    EXPECT_EQ(r.reversals, 0) << bend;
    EXPECT_NEAR(r.psi, DegToRad(bend), DegToRad(6.0)) << bend;
    // On the new axis within a few inches, and never near a wall (the base is 15 in across).
    EXPECT_NEAR(-r.x * uy + r.y * ux, 0.0, 8.0) << bend;
    EXPECT_GT(closest, 24.0) << bend;
  }
}

TEST(HallwayBehaviourTest, StartBesideAnOpenHallFollowsTheOtherWall) {
  // A 96 in corridor whose camera side opens into a hall 30 ft deep from x = -600 to
  // x = 0; the base starts in front of the hall, 13 in right of the axis and turned 10 deg
  // toward the far wall, before any width has been measured.
  Drive r({{{-2000, 48}, {-600, 48}}, {{-600, 48}, {-600, 408}}, {{-600, 408}, {0, 408}},
           {{0, 408}, {0, 48}}, {{0, 48}, {2000, 48}}, {{-2000, -48}, {2000, -48}}});
  r.x = -500.0;
  r.y = -13.0;
  r.psi = DegToRad(-10.0);
  double closest = 1e9;
  ASSERT_TRUE(r.Until(
      [&] {
        closest = std::min(closest, Clearance(r.walls, r.x, r.y));
        return r.x > 300.0;
      },
      60.0))
      << r.out.reason;
  EXPECT_GT(closest, 20.0);
  EXPECT_EQ(r.obstacle_stops, 0);
  EXPECT_NEAR(r.psi, 0.0, DegToRad(5.0));
}

TEST(HallwayBehaviourTest, SquaresUpToAWallItHeadsIntoInsteadOfWaitingBeforeIt) {
  // The base stands 17 in from the right wall, turned 25 deg into it, with the other side
  // open into a hall 30 ft deep (as where a corridor bends along an open side): the wall
  // stops it at once, and steering, which scales with the speed, cannot turn it. It turns
  // in place onto the wall's direction and goes on; it neither waits the obstacle patience
  // before the wall nor reverses.
  Drive r({{{-2000, 400}, {2000, 400}}, {{-2000, -48}, {2000, -48}}});
  r.y = -48.0 + 17.0;
  r.psi = DegToRad(-25.0);
  const double start_x = r.x;
  ASSERT_TRUE(r.Until([&] { return r.turns > 0; }, 1.0)) << r.out.reason;
  EXPECT_EQ(r.obstacle_stops, 1);
  EXPECT_THAT(r.out.reason, ::testing::HasSubstr("squaring up"));
  double closest = 1e9;
  ASSERT_TRUE(r.Until(
      [&] {
        closest = std::min(closest, Clearance(r.walls, r.x, r.y));
        return r.x > start_x + 240.0;
      },
      20.0))
      << r.out.reason;
  EXPECT_LT(r.t, r.b.config().obstacle_patience_s + 10.0);
  EXPECT_EQ(r.reversals, 0);
  EXPECT_EQ(r.turns, 1);
  EXPECT_GT(closest, Drive::kHeadRadiusIn);
  EXPECT_NEAR(r.psi, 0.0, DegToRad(5.0));
}

TEST(HallwayBehaviourTest, AtAJunctionTurnsTowardTheCameraSide) {
  // A T: the hallway ends against a crossing hallway between x = -60 and x = 60.
  Drive r({{{-2000, 60}, {-60, 60}}, {{-60, 60}, {-60, 2000}},
         {{-2000, -60}, {-60, -60}}, {{-60, -60}, {-60, -2000}},
         {{60, -2000}, {60, 2000}}});
  ASSERT_TRUE(r.Until([&] { return r.turns > 0; }, 60.0)) << r.out.reason;
  EXPECT_EQ(r.out.turn_kind, TurnKind::kJunction);
  ASSERT_TRUE(r.Until([&] { return r.y > 120.0; }, 30.0));
  EXPECT_NEAR(r.psi, kPi / 2.0, DegToRad(3.0));
}

TEST(HallwayBehaviourTest, WaitsBeforeSomeoneInTheHallwayAndResumesWhenTheyStepAside) {
  std::vector<Segment> walls = fake::Hallway(60);
  walls.push_back({{0, -8}, {0, 8}});  // someone standing on the axis
  Drive r(walls);
  ASSERT_TRUE(r.Until([&] { return r.out.state == BehaviourState::kObstacle; }, 60.0));
  EXPECT_EQ(r.obstacle_stops, 1);
  EXPECT_THAT(r.out.reason, ::testing::HasSubstr("obstacle"));
  // Held there: not reversed (it is not the hallway's end), not turned, one stop reported.
  ASSERT_FALSE(r.Until([&] { return r.out.state != BehaviourState::kObstacle; }, 3.0));
  EXPECT_NEAR(r.x, -60.0, 4.0);
  EXPECT_EQ(r.obstacle_stops, 1);
  EXPECT_EQ(r.reversals + r.turns, 0);
  r.walls.pop_back();  // they step aside
  ASSERT_TRUE(r.Until([&] { return r.x > 120.0; }, 30.0));
  EXPECT_EQ(r.out.state, BehaviourState::kFollowing);
}

TEST(HallwayBehaviourTest, BlockedCloseAheadReversesAfterThePatienceEvenIfTheStopFlickers) {
  // Something 20 in ahead, inside the stop distance, that the sonar loses for a scan now and
  // then (a wall met at an angle, an opening's edge): one blocked spell, not a new wait
  // after every flicker, and the way is taken for closed after the patience.
  Drive r(fake::Hallway(60));
  ASSERT_TRUE(r.Until([&] { return r.x > -200.0; }, 30.0));
  const double front = r.x + 20.0;
  const Segment thing{{front, -8}, {front, 8}};
  r.walls.push_back(thing);
  ASSERT_TRUE(r.Until([&] { return r.out.state == BehaviourState::kObstacle; }, 0.3)) << r.out.reason;
  const double blocked_at = r.t;
  const double patience = r.b.config().obstacle_patience_s;
  for (int second = 0; second < 8 && r.reversals == 0; ++second) {
    r.Until([&] { return r.reversals > 0; }, 0.8);
    if (r.reversals > 0) break;
    r.walls.pop_back();  // lost for 0.2 s
    r.Until([&] { return r.reversals > 0; }, 0.2);
    r.walls.push_back(thing);
  }
  ASSERT_EQ(r.reversals, 1) << r.out.reason;
  EXPECT_NEAR(r.t - blocked_at, patience, 0.2);
  EXPECT_EQ(r.b.travel_sign(), -1);
  EXPECT_GT(front - r.x, 7.5);  // never touched it
  EXPECT_THAT(r.out.reason, ::testing::HasSubstr("travel reversed"));
}

TEST(HallwayBehaviourTest, StopsAtOnceForSomethingSuddenlyClose) {
  Drive r(fake::Hallway(60));
  ASSERT_TRUE(r.Until([&] { return r.x > -200.0; }, 30.0));
  ASSERT_GT(r.out.linear_ftps, 2.5);
  const double front = r.x + 30.0;
  r.walls.push_back({{front, -8}, {front, 8}});  // someone steps out 30 in ahead
  ASSERT_TRUE(r.Until([&] { return r.out.state == BehaviourState::kObstacle; }, 0.3)) << r.out.reason;
  EXPECT_EQ(r.out.linear_ftps, 0.0);
  EXPECT_GT(front - r.x, 7.5);  // stopped clear of them
  EXPECT_EQ(r.obstacle_stops, 1);
}

TEST(HallwayBehaviourTest, AStallAgainstGlassTheSonarMissesReversesTravelAfterTheStallTime) {
  Drive r(fake::Hallway(60));
  r.glass_x = -250.0;
  ASSERT_TRUE(r.Until([&] { return r.x + Drive::kHeadRadiusIn > r.glass_x - 0.5; }, 30.0));
  const double contact_t = r.t;
  ASSERT_EQ(r.stalls, 0);
  ASSERT_TRUE(r.Until([&] { return r.stalls > 0; }, 5.0)) << r.out.reason;
  EXPECT_NEAR(r.t - contact_t, r.b.config().stall_time_s, 0.15);
  EXPECT_TRUE(r.out.reversed);
  EXPECT_EQ(r.out.linear_ftps, 0.0);
  EXPECT_EQ(r.b.travel_sign(), -1);
  EXPECT_THAT(r.out.reason, ::testing::HasSubstr("stalled: driven at 2.6 ft/s"));
  EXPECT_THAT(r.out.reason, ::testing::HasSubstr("travel reversed, now backward"));
  // The base then backs away from the glass, and stalls no more.
  const double stalled_x = r.x;
  ASSERT_TRUE(r.Until([&] { return r.x < stalled_x - 24.0; }, 5.0)) << r.out.reason;
  EXPECT_EQ(r.stalls, 1);
}

TEST(HallwayBehaviourTest, ABaseThatMovesSlowlyOrWaitsBeforeAnObstacleIsNotStalled) {
  // A base making a fifth of its commanded travel (a load, a slope) is slow, not stalled.
  Drive slow(fake::Hallway(60));
  slow.motion_gain = 0.2;
  slow.Until([] { return false; }, 20.0);
  EXPECT_EQ(slow.stalls, 0) << slow.out.reason;
  EXPECT_EQ(slow.reversals, 0);
  EXPECT_GT(slow.x, -400.0 + 60.0);
  // Stopped before something ahead, the base is not driven: no stall however long it waits.
  Drive r(fake::Hallway(60));
  ASSERT_TRUE(r.Until([&] { return r.x > -200.0; }, 30.0));
  r.walls.push_back({{r.x + 30.0, -8}, {r.x + 30.0, 8}});
  ASSERT_TRUE(r.Until([&] { return r.out.state == BehaviourState::kObstacle; }, 0.3));
  r.Until([] { return false; }, r.b.config().obstacle_patience_s - 0.5);
  EXPECT_EQ(r.stalls, 0) << r.out.reason;
  EXPECT_EQ(r.out.state, BehaviourState::kObstacle);
}

TEST(HallwayBehaviourTest, MissionDirectionSetsTheTravelAndNonFiniteInputHolds) {
  HallwayBehaviour b;
  b.OnScan(Scan(fake::Hallway(60), 0, 0, 0), 0.0);
  EXPECT_LT(b.Step(-1.0, 0.0, 0.0, 0.0, 0.05).linear_ftps, 0.0);
  EXPECT_EQ(b.travel_sign(), -1);
  const BehaviourOutput held = b.Step(std::nan(""), 0.0, 0.0, 0.05, 0.05);
  EXPECT_EQ(held.linear_ftps, 0.0);
  EXPECT_THAT(held.reason, ::testing::HasSubstr("non-finite"));
}

TEST(HallwayBehaviourTest, RejectsBadConfig) {
  HallwayBehaviourConfig c;
  c.turn_rate_radps = 0.0;
  EXPECT_THROW(HallwayBehaviour{c}, std::invalid_argument);
  c = {};
  c.turn_tolerance_deg = 90.0;
  EXPECT_THROW(HallwayBehaviour{c}, std::invalid_argument);
  c = {};
  c.frames_per_door = -1;
  EXPECT_THROW(HallwayBehaviour{c}, std::invalid_argument);
  c = {};
  c.camera_frame_period_s = 0.0;
  EXPECT_THROW(HallwayBehaviour{c}, std::invalid_argument);
  c = {};
  c.stall_travel_in = 3.0;  // as far as 1 s at 0.25 ft/s goes: every slow start would stall
  EXPECT_THROW(HallwayBehaviour{c}, std::invalid_argument);
  c = {};
  c.stall_time_s = 0.0;
  EXPECT_THROW(HallwayBehaviour{c}, std::invalid_argument);
  c = {};
  c.max_view_offset_in = 12.0;  // the whole envelope: a line on its edge
  EXPECT_THROW(HallwayBehaviour{c}, std::invalid_argument);
  c = {};
  c.view_offset_after_in = -1.0;
  EXPECT_THROW(HallwayBehaviour{c}, std::invalid_argument);
}

}  // namespace
}  // namespace stickrep::locomotion
