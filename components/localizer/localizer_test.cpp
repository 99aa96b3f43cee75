#include "localizer/localizer.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <tuple>
#include <utility>

#include "localizer/test_ring.h"

namespace stickrep::localizer {
namespace {

using ::testing::DoubleNear;

map::Map MakeMap(const std::vector<map::Edge>& edges) { return StraightRingMap(edges, "test"); }

// Drives along the straightened ring from `start_in` in steps of 6.24 in (one frame per
// 0.2 s at 2.6 ft/s), sighting every door whose centre is within `view_in` of the optical
// axis, and feeds the localizer. Returns the odometer when it first reports LOCALIZED, or
// a negative value. The odometer runs with `dir` (ring order forward) unless `odometer_sign`
// says which way the base drives (+1 forward, -1 backward) whichever way along the ring.
double DriveUntilLocalized(const map::Map& map, Localizer& loc, double start_in, int dir,
                           double max_travel_in, double view_in = 14.0, int odometer_sign = 0) {
  const int odo = odometer_sign != 0 ? odometer_sign : dir;
  const map::Ring& ring = map.ring(0);
  double length = 0.0;
  std::vector<double> centre;
  for (const auto& e : ring.edges) {
    centre.push_back(length + e.metric_in / 2.0);
    length += e.metric_in;
  }
  for (double travel = 0.0; travel <= max_travel_in; travel += 6.24) {
    const double axis = start_in + dir * travel;
    for (std::size_t i = 0; i < ring.edges.size(); ++i) {
      if (!ring.edges[i].IsDoor()) continue;
      for (double lap : {-length, 0.0, length}) {
        const double offset = centre[i] + lap - axis;  // along the ring order
        if (std::abs(offset) <= view_in) {
          loc.AddSighting({*ring.edges[i].door_class, ring.edges[i].metric_in, 0.9,
                           odo * (travel + dir * offset)});
        }
      }
    }
    loc.Advance(odo * travel);
    if (loc.estimate().status == Status::kLocalized) return travel;
  }
  return -1.0;
}

// Drives from odometer `odo_from` to `odo_to` (forward, or backward when odo_to is the
// smaller) with the optical axis at ring position `axis_from` at the start; the axis moves
// along the ring as the odometer does. Returns every status the localizer reported.
// `misread` (where given) gives the class a door edge is sighted as at an axis position,
// or nothing where it is missed.
std::vector<Status> DriveSegment(
    const map::Map& map, Localizer& loc, double axis_from, double odo_from, double odo_to,
    double view_in = 14.0,
    const std::function<std::optional<map::DoorClass>(int edge, double axis)>& misread = nullptr) {
  const map::Ring& ring = map.ring(0);
  double length = 0.0;
  std::vector<double> centre;
  for (const auto& e : ring.edges) {
    centre.push_back(length + e.metric_in / 2.0);
    length += e.metric_in;
  }
  std::vector<Status> statuses;
  const double step = odo_to >= odo_from ? 6.24 : -6.24;
  for (double odo = odo_from; step > 0 ? odo <= odo_to : odo >= odo_to; odo += step) {
    const double axis = axis_from + (odo - odo_from);
    for (std::size_t i = 0; i < ring.edges.size(); ++i) {
      if (!ring.edges[i].IsDoor()) continue;
      // The ring is closed: the door is seen on every lap.
      const double offset = std::remainder(centre[i] - axis, length);
      if (std::abs(offset) <= view_in) {
        const std::optional<map::DoorClass> read =
            misread ? misread(static_cast<int>(i), axis) : ring.edges[i].door_class;
        if (read) loc.AddSighting({*read, ring.edges[i].metric_in, 0.9, odo + offset});
      }
    }
    if (loc.Advance(odo)) statuses.push_back(loc.estimate().status);
  }
  return statuses;
}

// The ring edge at ring position `s` (ring order, wrapped).
int EdgeAtRingPosition(const map::Map& map, double s) {
  const map::Ring& ring = map.ring(0);
  double length = 0.0;
  for (const auto& e : ring.edges) length += e.metric_in;
  s = std::fmod(std::fmod(s, length) + length, length);
  for (int i = 0; i < ring.EdgeCount(); ++i) {
    if (s < ring.edges[i].metric_in) return i;
    s -= ring.edges[i].metric_in;
  }
  return ring.EdgeCount() - 1;
}

std::vector<map::Edge> DistinctHall() {
  using map::DoorClass;
  using map::Edge;
  return {Edge::Wall(120), Edge::Door(DoorClass::k36), Edge::Wall(80),  Edge::Door(DoorClass::k36),
          Edge::Wall(200), Edge::Door(DoorClass::k36), Edge::Wall(96),  Edge::Door(DoorClass::k40),
          Edge::Wall(150), Edge::Door(DoorClass::k36), Edge::Wall(64),  Edge::Door(DoorClass::k32)};
}

TEST(EdgeAssemblerTest, TwoDoorsGiveAPartialWallADoorAnExactWallAndADoor) {
  EdgeAssembler a;
  std::vector<map::SensedEdge> edges;
  // Doors centred at 100 (36 in) and 250 (40 in) along the wall; robot from 0 forward.
  for (double odo = 0.0; odo <= 320.0; odo += 6.0) {
    for (auto [centre, width] : {std::pair{100.0, 36.0}, std::pair{250.0, 40.0}}) {
      if (std::abs(centre - odo) < 12.0) {
        a.AddSighting({width == 36.0 ? map::DoorClass::k36 : map::DoorClass::k40, width, 0.8,
                       centre});
      }
    }
    for (const auto& e : a.Advance(odo)) edges.push_back(e);
  }
  ASSERT_EQ(edges.size(), 4u);
  EXPECT_EQ(edges[0].code, map::kWallCode);
  EXPECT_TRUE(edges[0].metric_is_lower_bound);
  EXPECT_THAT(edges[0].metric_in, DoubleNear(82.0, 1e-9));
  EXPECT_EQ(edges[1].code, map::DoorCode(map::DoorClass::k36));
  EXPECT_FALSE(edges[2].metric_is_lower_bound);
  EXPECT_THAT(edges[2].metric_in, DoubleNear(250.0 - 20.0 - 118.0, 1e-9));
  EXPECT_EQ(edges[3].code, map::DoorCode(map::DoorClass::k40));
}

TEST(EdgeAssemblerTest, SilenceRunsFromTheLastDoorToTheMarginOrTheFirstDoorInView) {
  EdgeAssemblerConfig config;
  config.silent_margin_in = 48.0;
  EdgeAssembler a(config);
  a.Advance(0.0);
  EXPECT_FALSE(a.silent_in().has_value());  // no edge yet
  // A 36 in door centred at 100: emitted once the axis is out_of_view_in past its centre.
  for (double odo = 6.0; odo <= 160.0; odo += 6.0) {
    if (std::abs(100.0 - odo) < 12.0) a.AddSighting({map::DoorClass::k36, 36.0, 0.8, 100.0});
    a.Advance(odo);
  }
  ASSERT_TRUE(a.last_edge_end_in().has_value());
  EXPECT_THAT(*a.last_edge_end_in(), DoubleNear(118.0, 1e-9));
  ASSERT_TRUE(a.silent_in().has_value());
  EXPECT_THAT(*a.silent_in(), DoubleNear(0.0, 1e-9));  // 160 - 48 is behind the far jamb
  a.Advance(250.0);
  EXPECT_THAT(*a.silent_in(), DoubleNear(250.0 - 48.0 - 118.0, 1e-9));
  // A door in view, not yet decided: the silence ends at its near jamb.
  // (Its centre 36 in behind the axis: within out_of_view_in, its near jamb behind the margin.)
  a.AddSighting({map::DoorClass::k36, 36.0, 0.8, 220.0});
  a.Advance(256.0);
  EXPECT_THAT(*a.silent_in(), DoubleNear(202.0 - 118.0, 1e-9));
}

TEST(EdgeAssemblerTest, FirstOdometerReadingAwayFromZeroStillGivesTheRightDirection) {
  EdgeAssembler a;
  a.Advance(500.0);
  a.Advance(506.0);
  EXPECT_EQ(a.travel_direction(), +1);
}

// Feeds sightings (centre, width, class, confidence) to an assembler while the robot drives
// forward from 0 to `to_in` in 6 in steps; each is seen while within 12 in of the axis.
struct Sighted {
  double centre, width;
  map::DoorClass cls;
  double confidence = 0.8;
  map::DoorMark mark = map::DoorMark::kUnknown;
};
std::vector<map::SensedEdge> Drive(EdgeAssembler& a, const std::vector<Sighted>& seen,
                                   double to_in = 300.0) {
  std::vector<map::SensedEdge> edges;
  for (double odo = 0.0; odo <= to_in; odo += 6.0) {
    for (const Sighted& s : seen) {
      if (std::abs(s.centre - odo) < 12.0) {
        a.AddSighting({s.cls, s.width, s.confidence, s.centre, s.mark});
      }
    }
    for (const auto& e : a.Advance(odo)) edges.push_back(e);
  }
  return edges;
}

TEST(EdgeAssemblerTest, TwoLeavesSharingTheStileBecomeOneDoubleDoorBySpan) {
  EdgeAssembler a;
  // A 36/36 double door spanning 100..172, its leaves 1 in apart at the stile; one leaf
  // reads 38 in and class 40, as a lone leaf often does.
  const auto edges = Drive(a, {{117.5, 35.0, map::DoorClass::k36},
                               {153.0, 34.0, map::DoorClass::k40}});
  ASSERT_EQ(edges.size(), 2u);
  EXPECT_EQ(edges[1].code, map::DoorCode(map::DoorClass::k36_36));
  EXPECT_THAT(edges[1].metric_in, DoubleNear(70.0, 1e-9));
}

// Drives from 0 to 300 in, frames every 6 in; each sighting is made once, in the frame at
// its odometer reading (a multiple of 6).
std::vector<map::SensedEdge> DriveOneFrameEach(
    EdgeAssembler& a, const std::vector<std::pair<double, DoorSighting>>& sightings) {
  std::vector<map::SensedEdge> edges;
  for (double odo = 0.0; odo <= 300.0; odo += 6.0) {
    for (const auto& [at, s] : sightings) {
      if (at == odo) a.AddSighting(s);
    }
    for (const auto& e : a.Advance(odo)) edges.push_back(e);
  }
  return edges;
}

TEST(EdgeAssemblerTest, LeavesSeenInOneFrameEachAreADoubleDoorNotTwoSpuriousTracks) {
  // The same 36/36 (leaves 100..136 and 136..172), each leaf paired in one frame only, as
  // the realistic renders often give a double door seen from the hallway axis.
  EdgeAssembler a;
  const auto edges = DriveOneFrameEach(a, {{114.0, {map::DoorClass::k36, 36.0, 0.6, 118.0}},
                                           {156.0, {map::DoorClass::k36, 36.0, 0.6, 154.0}}});
  ASSERT_EQ(edges.size(), 2u) << map::Describe(edges);
  EXPECT_EQ(edges[1].code, map::DoorCode(map::DoorClass::k36_36));
  EXPECT_THAT(edges[1].metric_in, DoubleNear(72.0, 1e-9));
}

TEST(EdgeAssemblerTest, TracksSeenOnceEachThatSpanNoDoubleDoorStaySpurious) {
  // Two one-frame tracks, alike and sharing a jamb, but 26 in each: together 52 in, no
  // double door's span. Both are dropped.
  EdgeAssembler a;
  const auto edges = DriveOneFrameEach(a, {{114.0, {map::DoorClass::k30, 26.0, 0.6, 113.0}},
                                           {138.0, {map::DoorClass::k30, 26.0, 0.6, 139.0}}});
  EXPECT_TRUE(edges.empty()) << map::Describe(edges);
}

TEST(EdgeAssemblerTest, TheLeafMarkIsTheMostReadOneWithUnreadFramesLeftOut) {
  EdgeAssembler a;
  std::vector<map::SensedEdge> edges;
  // A 36 in door centred at 100, seen in five frames: unread twice (the most of any one
  // answer), a poster twice, a window once.
  const map::DoorMark reads[] = {map::DoorMark::kUnknown, map::DoorMark::kPoster,
                                 map::DoorMark::kUnknown, map::DoorMark::kWindow,
                                 map::DoorMark::kPoster};
  int frame = 0;
  for (double odo = 0.0; odo <= 200.0; odo += 6.0) {
    if (std::abs(odo - 100.0) < 15.0 && frame < 5) {
      a.AddSighting({map::DoorClass::k36, 36.0, 0.8, 100.0, reads[frame++]});
    }
    for (const auto& e : a.Advance(odo)) edges.push_back(e);
  }
  ASSERT_EQ(frame, 5);
  ASSERT_EQ(edges.size(), 2u);
  EXPECT_EQ(edges[1].mark, map::DoorMark::kPoster);
  EXPECT_EQ(edges[0].mark, map::DoorMark::kUnknown);  // the wall before it
  EXPECT_EQ(map::Describe(edges[1]), "door36[poster]");
}

TEST(EdgeAssemblerTest, ADoubleDoorsMarkIsVotedOverBothLeavesAndUnreadStaysUnknown) {
  EdgeAssembler a;
  const auto edges = Drive(a, {{117.5, 35.0, map::DoorClass::k36, 0.8, map::DoorMark::kWindow},
                               {153.0, 34.0, map::DoorClass::k36, 0.8, map::DoorMark::kUnknown}});
  ASSERT_EQ(edges.size(), 2u);
  EXPECT_EQ(edges[1].code, map::DoorCode(map::DoorClass::k36_36));
  EXPECT_EQ(edges[1].mark, map::DoorMark::kWindow);
  EdgeAssembler unread;
  const auto plain = Drive(unread, {{118.0, 36.0, map::DoorClass::k36}});
  ASSERT_EQ(plain.size(), 2u);
  EXPECT_EQ(plain[1].mark, map::DoorMark::kUnknown);
}

TEST(EdgeAssemblerTest, LeavesSpanningSixtyInchesAreA30By30) {
  EdgeAssembler a;
  const auto edges = Drive(a, {{115.0, 30.0, map::DoorClass::k30},
                               {145.5, 30.0, map::DoorClass::k30}});
  ASSERT_EQ(edges.size(), 2u);
  EXPECT_EQ(edges[1].code, map::DoorCode(map::DoorClass::k30_30));
}

TEST(EdgeAssemblerTest, DoorsACasingApartAreNotADoubleDoor) {
  EdgeAssembler a;
  // 36 in doors at 100..136 and 139..175: 3 in of casing between, not a shared stile.
  const auto edges = Drive(a, {{118.0, 36.0, map::DoorClass::k36},
                               {157.0, 36.0, map::DoorClass::k36}});
  ASSERT_EQ(edges.size(), 3u);
  EXPECT_EQ(edges[1].code, map::DoorCode(map::DoorClass::k36));
  EXPECT_EQ(edges[2].code, map::DoorCode(map::DoorClass::k36));
}

TEST(EdgeAssemblerTest, OfOverlappingPairsTheBestSupportedIsTheDoor) {
  EdgeAssembler a;
  // The opening 100..136 (class 36), and the same door paired from a casing edge to a leaf
  // window's edge, 97..127 (class 30), seen as often but with less confidence.
  const auto edges = Drive(a, {{118.0, 36.0, map::DoorClass::k36, 0.25},
                               {112.0, 30.0, map::DoorClass::k30, 0.08}});
  ASSERT_EQ(edges.size(), 2u);
  EXPECT_EQ(edges[1].code, map::DoorCode(map::DoorClass::k36));
  EXPECT_THAT(edges[0].metric_in, DoubleNear(100.0, 1e-9));
}

TEST(EdgeAssemblerTest, TurnOfTheHeadingEndsTheWallAtACornerWithItsAngle) {
  EdgeAssembler a;
  std::vector<map::SensedEdge> edges;
  // 100 in of wall, a left turn (toward the camera's wall: a convex corner), 80 in, a door.
  for (double odo = 0.0; odo <= 300.0; odo += 6.0) {
    const double heading = odo >= 102.0 ? M_PI / 2.0 : 0.0;
    if (std::abs(odo - 200.0) < 12.0) a.AddSighting({map::DoorClass::k36, 36.0, 0.9, 200.0});
    for (const auto& e : a.Advance(odo, heading)) edges.push_back(e);
  }
  ASSERT_EQ(edges.size(), 3u);
  EXPECT_EQ(edges[0].code, map::kWallCode);
  EXPECT_TRUE(edges[0].metric_is_lower_bound);
  EXPECT_THAT(edges[0].metric_in, DoubleNear(102.0, 1e-9));
  EXPECT_EQ(edges[1].code, map::kWallCode);
  EXPECT_FALSE(edges[1].metric_is_lower_bound);
  EXPECT_DOUBLE_EQ(edges[1].angle_deg, 90.0);
  EXPECT_THAT(edges[1].metric_in, DoubleNear(182.0 - 102.0, 1e-9));
  EXPECT_EQ(edges[2].code, map::DoorCode(map::DoorClass::k36));
}

TEST(EdgeAssemblerTest, ACurvedWallFollowedAroundIsOneWallNotCorners) {
  // A quarter circle of radius 600 in on the axis (the heading turns 90 degrees over 942 in
  // of travel), with a door half way: one wall, the door, and the wall on; no corner.
  EdgeAssembler a;
  std::vector<map::SensedEdge> edges;
  const double arc = 600.0 * M_PI / 2.0;
  for (double odo = 0.0; odo <= arc + 120.0; odo += 6.0) {
    const double heading = std::min(odo, arc) / 600.0;
    if (std::abs(odo - 500.0) < 12.0) a.AddSighting({map::DoorClass::k36, 36.0, 0.9, 500.0});
    if (std::abs(odo - 1000.0) < 12.0) a.AddSighting({map::DoorClass::k32, 32.0, 0.9, 1000.0});
    for (const auto& e : a.Advance(odo, heading)) edges.push_back(e);
  }
  ASSERT_EQ(edges.size(), 4u);
  for (const auto& e : edges) EXPECT_TRUE(std::isnan(e.angle_deg)) << map::Describe(e);
  EXPECT_THAT(edges[2].metric_in, DoubleNear(1000.0 - 16.0 - 518.0, 1e-9));
}

TEST(EdgeAssemblerTest, AFortyDegreeTurnWithinAFootIsACorner) {
  // The follower steers round a 40 degree corner over 12 in: a corner (the hallway view
  // turns every bend over 30 degrees into one), then the new wall up to a door.
  EdgeAssembler a;
  std::vector<map::SensedEdge> edges;
  for (double odo = 0.0; odo <= 320.0; odo += 2.0) {
    const double heading = std::clamp((odo - 100.0) / 12.0, 0.0, 1.0) * 40.0 * M_PI / 180.0;
    if (std::abs(odo - 250.0) < 12.0) a.AddSighting({map::DoorClass::k36, 36.0, 0.9, 250.0});
    for (const auto& e : a.Advance(odo, heading)) edges.push_back(e);
  }
  ASSERT_EQ(edges.size(), 3u);
  EXPECT_TRUE(edges[0].metric_is_lower_bound);
  EXPECT_DOUBLE_EQ(edges[1].angle_deg, 90.0);
  EXPECT_EQ(edges[2].code, map::DoorCode(map::DoorClass::k36));
}

// Drives `before` in along a wall at `r1` from it, turns in place by `turn_rad` in 10
// steps of 3 degrees, then drives on with the new wall at `r2`, a 36 in door centred `door_after` in
// past the turn point. Returns the edges sensed.
std::vector<map::SensedEdge> DriveRoundCorner(double before, double r1, double turn_rad,
                                              double r2, double door_after) {
  EdgeAssembler a;
  std::vector<map::SensedEdge> edges;
  const auto take = [&](const std::vector<map::SensedEdge>& e) {
    edges.insert(edges.end(), e.begin(), e.end());
  };
  for (double odo = 0.0; odo <= before; odo += 6.0) {
    a.SetWallRange(r1);
    take(a.Advance(odo, 0.0));
  }
  for (int k = 1; k <= 30; ++k) {
    // Mid-turn ranges look across the corner: not a wall range. Within a few steps of
    // either end of the turn the sonar still sees the wall square enough.
    a.SetWallRange(k <= 3 ? r1 : k <= 26 ? 200.0 : r2);
    take(a.Advance(before, turn_rad * k / 30.0));
  }
  for (double odo = before + 6.0; odo <= before + door_after + 120.0; odo += 6.0) {
    a.SetWallRange(r2);
    const double centre = before + door_after;
    if (std::abs(centre - odo) < 12.0) a.AddSighting({map::DoorClass::k36, 36.0, 0.9, centre});
    take(a.Advance(odo, turn_rad));
  }
  return edges;
}

TEST(EdgeAssemblerTest, ConcaveCornerWallsRunOnToTheWallAheadAndBackFromTheNewFoot) {
  // Turning right (away from the camera's wall) 66 in before the wall ahead, 60 in from the
  // wall beside: the wall before ran 66 in past the optical axis, the wall after began
  // 60 in behind the new foot of the axis.
  const auto edges = DriveRoundCorner(120.0, 60.0, -M_PI / 2.0, 66.0, 100.0);
  ASSERT_EQ(edges.size(), 3u);
  EXPECT_TRUE(edges[0].metric_is_lower_bound);
  EXPECT_THAT(edges[0].metric_in, DoubleNear(120.0 + 66.0, 1e-9));
  EXPECT_DOUBLE_EQ(edges[1].angle_deg, 270.0);
  EXPECT_THAT(edges[1].metric_in, DoubleNear(60.0 + 100.0 - 18.0, 1e-9));
  EXPECT_EQ(edges[2].code, map::DoorCode(map::DoorClass::k36));
}

TEST(EdgeAssemblerTest, ConvexCornerWallEndsBehindTheAxisAndTheNextBeginsAhead) {
  // Turning left (toward the wall) after driving 54 in into the crossing: the wall before
  // ended 54 in back, the wall after begins 60 in ahead of the turn point.
  const auto edges = DriveRoundCorner(180.0, 60.0, M_PI / 2.0, 54.0, 100.0);
  ASSERT_EQ(edges.size(), 3u);
  EXPECT_THAT(edges[0].metric_in, DoubleNear(180.0 - 54.0, 1e-9));
  EXPECT_DOUBLE_EQ(edges[1].angle_deg, 90.0);
  EXPECT_THAT(edges[1].metric_in, DoubleNear(100.0 - 18.0 - 60.0, 1e-9));
}

TEST(EdgeAssemblerTest, DoorSightingsWhileTurningInPlaceAreIgnored) {
  EdgeAssembler a;
  a.Advance(0.0, 0.0);
  a.Advance(60.0, 0.0);
  a.Advance(60.0, 1.0);  // turning: past 45 degrees
  a.AddSighting({map::DoorClass::k36, 36.0, 0.9, 70.0});
  a.AddSighting({map::DoorClass::k36, 36.0, 0.9, 70.0});
  std::vector<map::SensedEdge> edges;
  for (double odo = 60.0; odo <= 260.0; odo += 6.0) {
    for (const auto& e : a.Advance(odo, M_PI / 2.0)) edges.push_back(e);
  }
  for (const auto& e : edges) EXPECT_EQ(e.code, map::kWallCode);
}

TEST(EdgeAssemblerTest, WallPanelFramedByTheCasingsOfTwoDoorsIsNotADoor) {
  EdgeAssembler a;
  std::vector<map::SensedEdge> edges;
  // Doors 100..136 and 182..218 with a 46 in wall between; the detector also pairs the
  // casings around the wall, a 40 in "door" from 139 to 179 (3 in casings).
  for (double odo = 0.0; odo <= 340.0; odo += 6.0) {
    for (auto [centre, width, cls] : {std::tuple{118.0, 36.0, map::DoorClass::k36},
                                      std::tuple{159.0, 40.0, map::DoorClass::k40},
                                      std::tuple{200.0, 36.0, map::DoorClass::k36}}) {
      if (std::abs(centre - odo) < 12.0) a.AddSighting({cls, width, 0.8, centre});
    }
    for (const auto& e : a.Advance(odo)) edges.push_back(e);
  }
  ASSERT_EQ(edges.size(), 4u);
  EXPECT_EQ(edges[1].code, map::DoorCode(map::DoorClass::k36));
  EXPECT_EQ(edges[2].code, map::kWallCode);
  EXPECT_THAT(edges[2].metric_in, DoubleNear(46.0, 1e-9));
  EXPECT_EQ(edges[3].code, map::DoorCode(map::DoorClass::k36));
}

// A row of 36 in doors 46 in apart (Engineering Building wing corridors): doors at 83, 165
// and 247 in, and between and before them the wall panels the detector pairs casing to
// casing, 40 in "doors" at 40, 122 and 204 in. `door_frames` and `panel_frames`: in how many
// frames each is sighted (a door's jambs are paired in more frames than a panel's casings).
std::vector<map::SensedEdge> DriveARow(EdgeAssembler& a, int door_frames, int panel_frames) {
  std::vector<map::SensedEdge> edges;
  for (double odo = 0.0; odo <= 380.0; odo += 6.0) {
    for (int i = 0; i < 3; ++i) {
      const double panel = 60.0 + 82.0 * i, door = 101.0 + 82.0 * i;
      // Sighted in the frames (every 6 in) whose axis is within 3 in times the count of its
      // centre, the far end left out.
      const auto sighted = [&](double centre, int frames) {
        return odo >= centre - 3.0 * frames && odo < centre + 3.0 * frames;
      };
      if (sighted(panel, panel_frames)) a.AddSighting({map::DoorClass::k40, 40.0, 0.8, panel});
      if (sighted(door, door_frames)) a.AddSighting({map::DoorClass::k36, 36.0, 0.8, door});
    }
    for (const auto& e : a.Advance(odo)) edges.push_back(e);
  }
  return edges;
}

TEST(EdgeAssemblerTest, ARowFirstSeenAtAWallPanelGivesItsDoorsNotItsPanels) {
  EdgeAssembler a;
  const std::vector<map::SensedEdge> edges = DriveARow(a, 4, 2);
  // A partial wall to the first door, then door, wall, door, wall, door: no 40 in "door".
  ASSERT_EQ(edges.size(), 6u) << map::Describe(edges);
  EXPECT_EQ(edges[0].code, map::kWallCode);
  EXPECT_TRUE(edges[0].metric_is_lower_bound);
  for (int i : {1, 3, 5}) EXPECT_EQ(edges[i].code, map::DoorCode(map::DoorClass::k36)) << i;
  for (int i : {2, 4}) {
    EXPECT_EQ(edges[i].code, map::kWallCode) << i;
    EXPECT_THAT(edges[i].metric_in, DoubleNear(46.0, 1e-9)) << i;
  }
}

TEST(EdgeAssemblerTest, ARowsFirstTrackIsKeptWhenTheNextIsNoBetterSupported) {
  // The same row with doors and panels sighted alike: the first track stands, as a door
  // seen before the row's first panel does (the support decides only when it differs).
  EdgeAssembler a;
  const std::vector<map::SensedEdge> edges = DriveARow(a, 3, 3);
  ASSERT_GE(edges.size(), 2u) << map::Describe(edges);
  EXPECT_EQ(edges[1].code, map::DoorCode(map::DoorClass::k40)) << map::Describe(edges);
}

TEST(EdgeAssemblerTest, TwoDoorsSideBySideWithNoRowAfterAreBothDoors) {
  // A 36 in door and a 30 in door a casing apart (Table 6.2's door-door adjacency), a wall
  // after: the first waits for the second, and both are doors with no wall between.
  EdgeAssembler a;
  std::vector<map::SensedEdge> edges;
  for (double odo = 0.0; odo <= 300.0; odo += 6.0) {
    if (std::abs(118.0 - odo) < 12.0) a.AddSighting({map::DoorClass::k36, 36.0, 0.8, 118.0});
    if (std::abs(156.0 - odo) < 9.0) a.AddSighting({map::DoorClass::k30, 30.0, 0.9, 156.0});
    for (const auto& e : a.Advance(odo)) edges.push_back(e);
  }
  ASSERT_EQ(edges.size(), 3u) << map::Describe(edges);
  EXPECT_EQ(edges[1].code, map::DoorCode(map::DoorClass::k36));
  EXPECT_EQ(edges[2].code, map::DoorCode(map::DoorClass::k30));
}

TEST(EdgeAssemblerTest, ReversedTravelRestartsTheSequenceTheOtherWay) {
  EdgeAssembler a;
  auto edges = Drive(a, {{100.0, 36.0, map::DoorClass::k36}}, 200.0);
  ASSERT_EQ(a.travel_direction(), +1);
  ASSERT_EQ(edges.size(), 2u);
  // Backing up from 198 in: over 12 in back the assembler turns round, once.
  a.Advance(190.0);
  EXPECT_FALSE(a.TakeReversal());
  a.Advance(185.0);
  EXPECT_TRUE(a.TakeReversal());
  EXPECT_FALSE(a.TakeReversal());
  EXPECT_EQ(a.travel_direction(), -1);
  EXPECT_TRUE(a.sequence().empty());
  // It went from the door's far jamb (118 in) to 198 in before turning back.
  EXPECT_THAT(a.reversal_travel_in(), DoubleNear(198.0 - 118.0, 1e-9));
  // The door is passed again the other way: a partial wall, then the door.
  std::vector<map::SensedEdge> back;
  for (double odo = 185.0; odo >= 0.0; odo -= 6.0) {
    if (std::abs(100.0 - odo) < 12.0) a.AddSighting({map::DoorClass::k36, 36.0, 0.8, 100.0});
    for (const auto& e : a.Advance(odo)) back.push_back(e);
  }
  ASSERT_EQ(back.size(), 2u);
  EXPECT_TRUE(back[0].metric_is_lower_bound);
  EXPECT_THAT(back[0].metric_in, DoubleNear(185.0 - 118.0, 1e-9));
  EXPECT_EQ(back[1].code, map::DoorCode(map::DoorClass::k36));
}

TEST(EdgeAssemblerTest, DoorSeenInOneFrameOnlyIsDroppedAsSpurious) {
  EdgeAssembler a;
  a.Advance(0.0);
  a.AddSighting({map::DoorClass::k36, 36.0, 0.8, 30.0});
  EXPECT_TRUE(a.Advance(200.0).empty());
}

TEST(EdgeAssemblerTest, BackwardTravelOrdersEdgesByDecreasingPosition) {
  EdgeAssembler a;
  std::vector<map::SensedEdge> edges;
  for (double odo = 0.0; odo >= -320.0; odo -= 6.0) {
    for (auto [centre, width] : {std::pair{-100.0, 36.0}, std::pair{-250.0, 40.0}}) {
      if (std::abs(centre - odo) < 12.0) {
        a.AddSighting({width == 36.0 ? map::DoorClass::k36 : map::DoorClass::k40, width, 0.8,
                       centre});
      }
    }
    for (const auto& e : a.Advance(odo)) edges.push_back(e);
  }
  ASSERT_EQ(edges.size(), 4u);
  EXPECT_EQ(edges[1].code, map::DoorCode(map::DoorClass::k36));
  EXPECT_EQ(edges[3].code, map::DoorCode(map::DoorClass::k40));
  EXPECT_THAT(edges[2].metric_in, DoubleNear(112.0, 1e-9));
}

TEST(LocalizerTest, ExactSightingsForwardRecoverTheTruePose) {
  const map::Map map = MakeMap(DistinctHall());
  Localizer loc(map);
  ASSERT_GT(DriveUntilLocalized(map, loc, 10.0, +1, 3000.0), 0.0);
  const Hypothesis& h = loc.estimate().hypotheses.front();
  EXPECT_EQ(loc.estimate().candidates, 1u);
  EXPECT_EQ(h.dir, +1);
  EXPECT_EQ(loc.restarts(), 0u);
}

TEST(LocalizerTest, ExactSightingsBackwardRecoverTheReverseDirection) {
  const map::Map map = MakeMap(DistinctHall());
  Localizer loc(map);
  ASSERT_GT(DriveUntilLocalized(map, loc, 900.0, -1, 3000.0), 0.0);
  EXPECT_EQ(loc.estimate().hypotheses.front().dir, -1);
}

// The Bayes localizer with the paper's error model (Table 6.10) for `map`.
LocalizerConfig PaperBayesConfig(const map::Map& map) {
  LocalizerConfig config;
  config.method = MatchMethod::kBayes;
  config.bayes.confusion = recovery::Resolve(
      recovery::LoadErrorModel(std::string(STICKREP_SOURCE_DIR) + "/configs/error_model_paper.yaml"),
      map::MatchIndex(map));
  return config;
}

TEST(LocalizerTest, BayesMethodRecoversTheTruePoseFromExactSightings) {
  const map::Map map = MakeMap(DistinctHall());
  const LocalizerConfig config = PaperBayesConfig(map);
  Localizer loc(map, config);
  ASSERT_GT(DriveUntilLocalized(map, loc, 10.0, +1, 6000.0), 0.0);
  const Hypothesis& h = loc.estimate().hypotheses.front();
  EXPECT_EQ(h.dir, +1);
  EXPECT_GE(loc.estimate().confidence, config.bayes.settings.threshold);
}

// The camera looks left and a ring is listed with its wall on the right: a base driving
// forward walks the ring against its order. Told so, the filter weighs that direction alone.
TEST(LocalizerTest, TheTravelDirectionFollowsFromTheOdometersSignWhenTheSettingsSaySo) {
  const map::Map map = MakeMap(DistinctHall());
  LocalizerConfig config = PaperBayesConfig(map);
  config.direction_from_travel = true;
  // Against the ring order, driving forward: found, against the ring order.
  Localizer forward(map, config);
  ASSERT_GT(DriveUntilLocalized(map, forward, 900.0, -1, 6000.0, 14.0, +1), 0.0);
  EXPECT_EQ(forward.estimate().hypotheses.front().dir, -1);
  // The same path driven backward: the filter holds the ring order alone, so it never names
  // the true direction.
  Localizer backward(map, config);
  DriveUntilLocalized(map, backward, 900.0, -1, 6000.0, 14.0, -1);
  ASSERT_FALSE(backward.estimate().hypotheses.empty());
  for (const Hypothesis& h : backward.estimate().hypotheses) EXPECT_EQ(h.dir, +1);
}

TEST(LocalizerTest, PoseIsMaintainedEdgeByEdgeAfterLocalization) {
  const map::Map map = MakeMap(DistinctHall());
  Localizer loc(map);
  const auto statuses = DriveSegment(map, loc, 10.0, 0.0, 2400.0);
  ASSERT_FALSE(statuses.empty());
  EXPECT_EQ(statuses.back(), Status::kLocalized);
  EXPECT_EQ(loc.losses(), 0u);
  EXPECT_EQ(std::count(statuses.begin(), statuses.end(), Status::kLost), 0);
}

TEST(LocalizerTest, KidnappedRobotIsDetectedAsLostAndRecoversAgain) {
  const map::Map map = MakeMap(DistinctHall());
  Localizer loc(map);
  DriveSegment(map, loc, 10.0, 0.0, 1400.0);
  ASSERT_EQ(loc.estimate().status, Status::kLocalized);
  // Teleported half a lap away: the anticipated edges stop coming.
  const auto after = DriveSegment(map, loc, 10.0 + 1400.0 + 463.0, 1406.24, 6000.0);
  EXPECT_GE(loc.losses(), 1u);
  EXPECT_NE(std::find(after.begin(), after.end(), Status::kLost), after.end());
  EXPECT_EQ(after.back(), Status::kLocalized) << loc.estimate().message << " restarts "
                                             << loc.restarts() << " edges " << loc.edges_total();
}

TEST(LocalizerTest, PoseIsKeptWhenTheTravelReverses) {
  const map::Map map = MakeMap(DistinctHall());
  Localizer loc(map);
  DriveSegment(map, loc, 10.0, 0.0, 1400.0);
  ASSERT_EQ(loc.estimate().status, Status::kLocalized);
  ASSERT_EQ(loc.estimate().hypotheses.front().dir, +1);
  // Back the way it came (a goal behind it): the pose is kept and turned round, and the
  // doors met on the way back confirm it.
  const auto back = DriveSegment(map, loc, 10.0 + 1400.0, 1400.0, 300.0);
  EXPECT_EQ(std::find(back.begin(), back.end(), Status::kLost), back.end());
  EXPECT_EQ(loc.losses(), 0u);
  ASSERT_EQ(loc.estimate().status, Status::kLocalized);
  const Hypothesis& h = loc.estimate().hypotheses.front();
  EXPECT_EQ(h.dir, -1);
  const int truth = EdgeAtRingPosition(map, 10.0 + 300.0);
  const int n = map.ring(0).EdgeCount();
  const int de = std::abs(h.edge - truth);
  EXPECT_TRUE(de <= 1 || de == n - 1) << "pose edge " << h.edge << ", truth " << truth;
}

TEST(LocalizerTest, KidnappedWhileTravellingBackIsStillNoticed) {
  const map::Map map = MakeMap(DistinctHall());
  Localizer loc(map);
  DriveSegment(map, loc, 10.0, 0.0, 1400.0);
  DriveSegment(map, loc, 1410.0, 1400.0, 1000.0);
  ASSERT_EQ(loc.estimate().status, Status::kLocalized);
  // Teleported half a lap while backing: the anticipated doors stop coming.
  const auto after = DriveSegment(map, loc, 1010.0 + 463.0, 993.76, -4000.0);
  EXPECT_GE(loc.losses(), 1u);
  EXPECT_NE(std::find(after.begin(), after.end(), Status::kLost), after.end());
  EXPECT_EQ(after.back(), Status::kLocalized) << loc.estimate().message;
}

// The Bayes localizer as configs/localizer.yaml sets it up for a held pose: a kidnap share
// per edge, the hold and LOST thresholds.
LocalizerConfig HoldingBayesConfig(const map::Map& map, double lost_threshold,
                                   int lost_confirm_edges = 0) {
  LocalizerConfig config = PaperBayesConfig(map);
  config.bayes.settings.kidnap_per_edge = 0.01;
  config.keep_threshold = 0.9;
  config.lost_threshold = lost_threshold;
  config.lost_confirm_edges = lost_confirm_edges;
  return config;
}

// Kidnapped half a lap on the small hall: returns the localizer after the pose was given up
// and found again at the new place, and every status it reported after the kidnap.
std::pair<std::unique_ptr<Localizer>, std::vector<Status>> Kidnapped(const map::Map& map,
                                                                     double lost_threshold,
                                                                     int lost_confirm_edges = 0) {
  auto loc =
      std::make_unique<Localizer>(map, HoldingBayesConfig(map, lost_threshold, lost_confirm_edges));
  DriveSegment(map, *loc, 10.0, 0.0, 1400.0);
  EXPECT_EQ(loc->estimate().status, Status::kLocalized);
  EXPECT_FALSE(loc->given_up().has_value());
  auto after = DriveSegment(map, *loc, 10.0 + 1400.0 + 463.0, 1406.24, 6000.0);
  return {std::move(loc), std::move(after)};
}

// Kidnapped half a lap on the small hall as in Kidnapped(), driven step by step: the
// odometer reading at which the held pose was first given up (infinite: never), and the
// localizer then.
std::pair<double, std::unique_ptr<Localizer>> GivenUpAfterAKidnap(const map::Map& map,
                                                                  const LocalizerConfig& config) {
  auto loc = std::make_unique<Localizer>(map, config);
  DriveSegment(map, *loc, 10.0, 0.0, 1400.0);
  EXPECT_EQ(loc->estimate().status, Status::kLocalized);
  for (double odo = 1406.24; odo <= 6000.0; odo += 6.24) {
    DriveSegment(map, *loc, 10.0 + 1400.0 + 463.0 + (odo - 1406.24), odo, odo);
    if (loc->estimate().status != Status::kLocalized) return {odo, std::move(loc)};
  }
  return {std::numeric_limits<double>::infinity(), std::move(loc)};
}

TEST(LocalizerTest, TheSilenceWhereTheHeldPlaceHasADoorGivesAKidnappedPoseUpSooner) {
  const map::Map map = MakeMap(DistinctHall());
  const LocalizerConfig edges_only = HoldingBayesConfig(map, 1e-3, 1);
  LocalizerConfig with_silence = edges_only;
  with_silence.silence_tests_pose = true;
  const auto [by_edges, a] = GivenUpAfterAKidnap(map, edges_only);
  const auto [by_silence, b] = GivenUpAfterAKidnap(map, with_silence);
  ASSERT_TRUE(std::isfinite(by_edges));
  EXPECT_LT(by_silence, by_edges);
  EXPECT_NE(b->estimate().message.find("the silence"), std::string::npos) << b->estimate().message;
  // The silence gives the pose up; it never says LOST on its own.
  EXPECT_EQ(b->estimate().status, Status::kRecovering);
  ASSERT_TRUE(b->given_up().has_value());
  EXPECT_FALSE(b->given_up()->lost);
}

TEST(LocalizerTest, TheSilenceGivesUpNoPoseWhoseDoorsComeAsTheMapHasThem) {
  const map::Map map = MakeMap(DistinctHall());
  LocalizerConfig config = HoldingBayesConfig(map, 1e-3, 1);
  config.silence_tests_pose = true;
  Localizer loc(map, config);
  DriveSegment(map, loc, 10.0, 0.0, 1400.0);
  ASSERT_EQ(loc.estimate().status, Status::kLocalized);
  const std::vector<Status> after = DriveSegment(map, loc, 10.0 + 1400.0, 1400.0, 6000.0);
  EXPECT_EQ(std::count(after.begin(), after.end(), Status::kLocalized),
            static_cast<long>(after.size()))
      << loc.estimate().message;
  EXPECT_FALSE(loc.given_up().has_value());
}

TEST(LocalizerTest, APoseDeclaredOnTheSilenceIsTestedFromThePlaceTheFilterHolds) {
  // Declared on the silence past the last edge (bayes_confirm_silent_in), the tracker starts
  // edges beyond the filter's place; the silence that follows is weighed from that place.
  const map::Map map = MakeMap(DistinctHall());
  LocalizerConfig config = HoldingBayesConfig(map, 1e-3, 1);
  config.bayes.settings.confirm_silent_in = 60.0;
  config.silence_tests_pose = true;
  int declared_on_silence = 0;
  for (double start = 0.0; start < 926.0; start += 50.0) {
    Localizer loc(map, config);
    double odo = 0.0;
    for (; odo <= 1400.0 && loc.estimate().status != Status::kLocalized; odo += 6.24) {
      DriveSegment(map, loc, start + odo, odo, odo);
    }
    ASSERT_EQ(loc.estimate().status, Status::kLocalized) << "start " << start;
    if (loc.estimate().message.find("sensed past the last edge") == std::string::npos) continue;
    ++declared_on_silence;
    const std::vector<Status> after = DriveSegment(map, loc, start + odo, odo, odo + 4600.0);
    EXPECT_EQ(std::count(after.begin(), after.end(), Status::kLocalized),
              static_cast<long>(after.size()))
        << "start " << start << ": " << loc.estimate().message;
    EXPECT_FALSE(loc.given_up().has_value()) << "start " << start;
  }
  EXPECT_GT(declared_on_silence, 0);
}

TEST(LocalizerTest, AHeldPoseWhoseAnticipatedDoorsDoNotComeIsNeverPublishedAsLocalizedAndLost) {
  // Under the filter the tracker's own LOST (three anticipated doors not seen) loses only its
  // anchor: the pose stays LOCALIZED until the filter weighs the next edge, and what is
  // published with it must not say LOST.
  const map::Map map = MakeMap(DistinctHall());
  Localizer loc(map, HoldingBayesConfig(map, 1e-3, 1));
  DriveSegment(map, loc, 10.0, 0.0, 1400.0);
  ASSERT_EQ(loc.estimate().status, Status::kLocalized);
  int anchor_lost = 0;
  for (double odo = 1406.24; odo <= 2400.0; odo += 6.24) {
    DriveSegment(map, loc, 10.0 + odo, odo, odo, /*view_in=*/-1.0);  // no door is seen
    const PoseEstimate& e = loc.estimate();
    if (e.status != Status::kLocalized) continue;
    EXPECT_EQ(e.message.find("LOST"), std::string::npos) << "odometer " << odo << ": " << e.message;
    if (e.message.find("anticipated edges in a row not seen") != std::string::npos) ++anchor_lost;
  }
  EXPECT_GT(anchor_lost, 0) << loc.estimate().message;
}

TEST(LocalizerTest, APoseGivenUpIsLostOnlyWhenTheFiltersBeliefInItIsUnderTheLostThreshold) {
  const map::Map map = MakeMap(DistinctHall());
  // The same kidnap, the same evidence: given up RECOVERING under a low LOST threshold...
  const auto [recovering, after_low] = Kidnapped(map, 1e-3);
  ASSERT_TRUE(recovering->given_up().has_value());
  const Localizer::GivenUp g = *recovering->given_up();
  EXPECT_EQ(g.serial, 1u);
  EXPECT_EQ(g.dir, +1);
  EXPECT_GE(g.belief, 1e-3);
  EXPECT_FALSE(g.lost);
  EXPECT_EQ(recovering->losses(), 0u);
  EXPECT_EQ(std::find(after_low.begin(), after_low.end(), Status::kLost), after_low.end());
  EXPECT_NE(std::find(after_low.begin(), after_low.end(), Status::kRecovering), after_low.end());
  EXPECT_EQ(after_low.back(), Status::kLocalized) << recovering->estimate().message;
  // ...and LOST under one above the belief it had then.
  const auto [lost, after_high] = Kidnapped(map, std::min(0.999, g.belief + 0.01));
  ASSERT_TRUE(lost->given_up().has_value());
  EXPECT_DOUBLE_EQ(lost->given_up()->belief, g.belief);
  EXPECT_TRUE(lost->given_up()->lost);
  EXPECT_EQ(lost->losses(), 1u);
  EXPECT_NE(std::find(after_high.begin(), after_high.end(), Status::kLost), after_high.end());
  EXPECT_EQ(after_high.back(), Status::kLocalized) << lost->estimate().message;
}

// Held on the small hall, then one lap on a door is sighted in the middle of the 200 in wall
// (ring 272-472 in of the 926 in lap) that is not there: a misread, not a kidnap. Returns
// every status reported from then on.
std::vector<Status> PastAFalseDoor(const map::Map& map, Localizer& loc) {
  DriveSegment(map, loc, 10.0, 0.0, 1400.0);
  EXPECT_EQ(loc.estimate().status, Status::kLocalized);
  std::vector<Status> all;
  for (double odo = 1406.24; odo <= 4000.0; odo += 6.24) {
    const double axis = 10.0 + odo;
    const double from_false_door = std::remainder(axis - 372.0, 926.0);
    if (axis < 2500.0 && std::abs(from_false_door) < 12.0) {
      loc.AddSighting({map::DoorClass::k30, 30.0, 0.9, odo - from_false_door});
    }
    const auto s = DriveSegment(map, loc, axis, odo, odo);
    all.insert(all.end(), s.begin(), s.end());
  }
  return all;
}

TEST(LocalizerTest, ARightPoseGivenUpOnAFalseDoorIsFoundAgainWithoutALost) {
  const map::Map map = MakeMap(DistinctHall());
  Localizer loc(map, HoldingBayesConfig(map, 1e-3));
  const std::vector<Status> all = PastAFalseDoor(map, loc);
  // The false door did make the filter unsure: the pose was given up, not LOST.
  ASSERT_TRUE(loc.given_up().has_value());
  EXPECT_GE(loc.given_up()->belief, 1e-3);
  EXPECT_GE(std::count(all.begin(), all.end(), Status::kRecovering), 1);
  EXPECT_FALSE(loc.given_up()->lost);
  EXPECT_EQ(std::count(all.begin(), all.end(), Status::kLost), 0) << loc.estimate().message;
  EXPECT_EQ(loc.losses(), 0u);
  EXPECT_EQ(loc.estimate().status, Status::kLocalized) << loc.estimate().message;
}

// Held on the small hall, then one lap on its one 40 in door (edge 7) is read as a 32: a
// misread the map's other places explain no better. Returns every status from then on.
std::vector<Status> PastAMisreadDoor(const map::Map& map, Localizer& loc) {
  DriveSegment(map, loc, 10.0, 0.0, 1400.0);
  EXPECT_EQ(loc.estimate().status, Status::kLocalized);
  return DriveSegment(map, loc, 10.0 + 1400.0, 1400.0, 4000.0, 14.0,
                      [&](int edge, double axis) -> std::optional<map::DoorClass> {
                        return edge == 7 && axis < 2500.0 ? map::DoorClass::k32
                                                          : *map.ring(0).edges[edge].door_class;
                      });
}

TEST(LocalizerTest, APoseSunkByOneMisreadIsNotLostWhenTheNextEdgesAreNotAgainstIt) {
  const map::Map map = MakeMap(DistinctHall());
  // The misread door sinks the right pose's belief; a LOST threshold above it says LOST at
  // once...
  Localizer at_once(map, HoldingBayesConfig(map, 1e-3));
  PastAMisreadDoor(map, at_once);
  ASSERT_TRUE(at_once.given_up().has_value());
  const double sunk = at_once.given_up()->belief;
  const double threshold = (sunk + 0.9) / 2.0;  // above it, under the keep threshold
  ASSERT_LT(sunk, 0.85);
  Localizer eager(map, HoldingBayesConfig(map, threshold));
  const std::vector<Status> eager_all = PastAMisreadDoor(map, eager);
  ASSERT_TRUE(eager.given_up().has_value());
  EXPECT_TRUE(eager.given_up()->lost);
  EXPECT_GE(eager.losses(), 1u);
  EXPECT_GE(std::count(eager_all.begin(), eager_all.end(), Status::kLost), 1);
  // ...where waiting for the next edge does not: the wall and door after the misread one
  // are the map's, and the belief in the pose given up rises back over the threshold.
  Localizer patient(map, HoldingBayesConfig(map, threshold, 1));
  const std::vector<Status> patient_all = PastAMisreadDoor(map, patient);
  ASSERT_TRUE(patient.given_up().has_value());
  EXPECT_DOUBLE_EQ(patient.given_up()->belief, sunk);
  EXPECT_FALSE(patient.given_up()->lost);
  EXPECT_EQ(patient.losses(), 0u);
  EXPECT_EQ(std::count(patient_all.begin(), patient_all.end(), Status::kLost), 0)
      << patient.estimate().message;
  EXPECT_EQ(patient.estimate().status, Status::kLocalized) << patient.estimate().message;
}

TEST(LocalizerTest, AKidnappedPoseIsStillLostWhenTheNextEdgesAreAgainstItToo) {
  const map::Map map = MakeMap(DistinctHall());
  const auto [at_once, statuses] = Kidnapped(map, 1e-3);
  ASSERT_TRUE(at_once->given_up().has_value());
  const double threshold = std::min(0.999, at_once->given_up()->belief + 0.01);
  // Half a lap away every edge after the one that sank the pose is against it as well: LOST
  // is said, an edge later.
  const auto [patient, after] = Kidnapped(map, threshold, 1);
  ASSERT_TRUE(patient->given_up().has_value());
  EXPECT_TRUE(patient->given_up()->lost);
  EXPECT_EQ(patient->losses(), 1u);
  const auto recovering = std::find(after.begin(), after.end(), Status::kRecovering);
  const auto lost = std::find(after.begin(), after.end(), Status::kLost);
  ASSERT_NE(lost, after.end()) << patient->estimate().message;
  EXPECT_LT(recovering, lost) << "RECOVERING first, LOST once the next edge is against it";
  EXPECT_EQ(after.back(), Status::kLocalized) << patient->estimate().message;
}

TEST(LocalizerTest, APoseSunkByTheSameDoorsMissedPassAfterPassIsNotLostWhenTheNextEdgesRaiseIt) {
  // Held on the small hall, then for two laps its 36 in doors at edges 3 and 5 and its 40 in
  // door at edge 7 are never seen (a stretch the camera misses every time it passes, not a
  // kidnap). The misses sink the right pose; the edges after them are the map's and raise
  // the belief in it again, though not over a LOST threshold set high enough to leave it
  // under: those edges are for the pose, so no LOST, only RECOVERING.
  const map::Map map = MakeMap(DistinctHall());
  Localizer loc(map, HoldingBayesConfig(map, /*lost_threshold=*/0.89, /*lost_confirm_edges=*/1));
  DriveSegment(map, loc, 10.0, 0.0, 1400.0);
  ASSERT_EQ(loc.estimate().status, Status::kLocalized);
  const std::vector<Status> after =
      DriveSegment(map, loc, 10.0 + 1400.0, 1400.0, 5000.0, 14.0,
                   [&](int edge, double axis) -> std::optional<map::DoorClass> {
                     if ((edge == 3 || edge == 5 || edge == 7) && axis < 3300.0)
                       return std::nullopt;
                     return map.ring(0).edges[edge].door_class;
                   });
  ASSERT_TRUE(loc.given_up().has_value());
  const Localizer::GivenUp g = *loc.given_up();
  EXPECT_EQ(g.serial, 1u);
  // Given up under the LOST threshold, and one edge on still under it, but higher.
  EXPECT_LT(g.belief, 0.89);
  ASSERT_TRUE(g.belief_on.has_value());
  EXPECT_LT(*g.belief_on, 0.89);
  EXPECT_GT(*g.belief_on, g.belief);
  EXPECT_FALSE(g.lost);
  EXPECT_EQ(loc.losses(), 0u);
  EXPECT_EQ(std::count(after.begin(), after.end(), Status::kLost), 0);
  EXPECT_GE(std::count(after.begin(), after.end(), Status::kRecovering), 1);
  EXPECT_EQ(loc.estimate().status, Status::kLocalized) << loc.estimate().message;
}

TEST(LocalizerTest, SequenceThatFitsNowhereIsDiscardedAndRecoveryStartsAgain) {
  const map::Map map = MakeMap(DistinctHall());
  Localizer loc(map);
  loc.Advance(0.0);
  // A door40 followed by a door32 after 20 in of wall appears nowhere on the map.
  for (double odo = 0.0; odo <= 200.0; odo += 6.0) {
    if (std::abs(odo - 60.0) < 12.0) loc.AddSighting({map::DoorClass::k40, 40.0, 0.9, 60.0});
    if (std::abs(odo - 110.0) < 12.0) loc.AddSighting({map::DoorClass::k32, 32.0, 0.9, 110.0});
    loc.Advance(odo);
  }
  EXPECT_GE(loc.restarts(), 1u);
  EXPECT_NE(loc.estimate().status, Status::kLocalized);
}

}  // namespace
}  // namespace stickrep::localizer
