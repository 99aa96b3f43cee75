#include "localizer/pose_tracker.h"

#include "localizer/test_ring.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace stickrep::localizer {
namespace {

using map::DoorClass;
using map::Edge;

// A closed ring with irregular door spacing, so that no stretch of it looks like another:
// 8 doors of four classes between walls of 45 to 150 in (1112 in round).
map::Map TrackMap() {
  const std::vector<Edge> edges = {
      Edge::Wall(60), Edge::Door(DoorClass::k36), Edge::Wall(90),  Edge::Door(DoorClass::k30),
      Edge::Wall(45), Edge::Door(DoorClass::k40), Edge::Wall(120), Edge::Door(DoorClass::k32),
      Edge::Wall(70), Edge::Door(DoorClass::k36), Edge::Wall(150), Edge::Door(DoorClass::k30),
      Edge::Wall(80), Edge::Door(DoorClass::k36), Edge::Wall(100), Edge::Door(DoorClass::k40)};
  return StraightRingMap(edges, "track");
}

// One door the robot passes, in travel coordinates (inches travelled since the start).
struct PassedDoor {
  double near_in, far_in;
  map::SymbolCode code;
};

// Where things are when the robot travels the ring from (edge, offset) in direction dir:
// the doors it passes and the true edge at a given travel.
class Walk {
 public:
  Walk(const map::Map& map, int edge, int dir, double offset_in)
      : map_(map), start_{0, edge, dir}, offset_in_(offset_in) {}

  const map::Map& map() const { return map_; }

  // Doors (and their positions) met within `travel_in`, plus the cursor at a given travel.
  std::vector<PassedDoor> Doors(double from_in, double to_in) const {
    std::vector<PassedDoor> out;
    map::Cursor c = start_;
    double start = -offset_in_;
    while (start < to_in) {
      const Edge& e = map_.EdgeAt(c.ring, c.edge);
      if (e.IsDoor() && start + e.metric_in / 2.0 >= from_in) {
        out.push_back({start, start + e.metric_in, map::CodeOf(e)});
      }
      start += e.metric_in;
      map_.Advance(c);
    }
    return out;
  }
  TrackedPose At(double travel_in) const {
    map::Cursor c = start_;
    double along = travel_in + offset_in_;
    while (along >= map_.EdgeAt(c.ring, c.edge).metric_in) {
      along -= map_.EdgeAt(c.ring, c.edge).metric_in;
      map_.Advance(c);
    }
    return {c.ring, c.edge, c.dir, along};
  }

 private:
  const map::Map& map_;
  map::Cursor start_;
  double offset_in_;
};

// Drives the tracker as the edge assembler would: a door is reported 48 in past its centre
// with the wall since the previous door, both measured by an odometer with `scale` error.
struct Drive {
  double step_in = 6.24;  // one frame per 0.2 s at 2.6 ft/s
  double odometer_scale = 1.02;
  int odometer_sign = +1;
  double odometer_start_in = 500.0;
};

struct Outcome {
  int doors_reported = 0;
  int doors_after_kidnap_until_lost = -1;
  bool pose_always_right = true;
};

// `doors` in travel coordinates (already edited for false or missed doors / the kidnap);
// `truth` tells the true edge at each travel for the check, until `check_until_in`.
Outcome DriveAlong(PoseTracker& tracker, std::vector<PassedDoor> doors, const Walk& truth,
                   double travel_in, const Drive& d, double kidnap_at_in = 1e18,
                   double check_until_in = 1e18) {
  Outcome out;
  auto odo = [&](double p) { return d.odometer_start_in + d.odometer_sign * d.odometer_scale * p; };
  EXPECT_TRUE(tracker.Start(truth.At(0.0), odo(0.0), d.odometer_sign));
  std::size_t next = 0;
  double prev_far = -truth.At(0.0).offset_in;  // tests start in a wall just past a door
  int after_kidnap = 0;
  for (double p = 0.0; p <= travel_in; p += d.step_in) {
    std::vector<map::SensedEdge> batch;
    double last_end = 0.0;
    while (next < doors.size() && (doors[next].near_in + doors[next].far_in) / 2.0 + 48.0 <= p) {
      const PassedDoor& door = doors[next++];
      map::SensedEdge wall;
      wall.code = map::kWallCode;
      wall.metric_in = (door.near_in - prev_far) * d.odometer_scale;
      batch.push_back(wall);
      map::SensedEdge e;
      e.code = door.code;
      e.metric_in = (door.far_in - door.near_in) * d.odometer_scale;
      batch.push_back(e);
      last_end = odo(door.far_in);
      prev_far = door.far_in;
      ++out.doors_reported;
      if (door.near_in >= kidnap_at_in) ++after_kidnap;
    }
    if (!batch.empty()) tracker.OnEdges(batch, last_end);
    tracker.Advance(odo(p));
    if (tracker.status() == TrackStatus::kLost && out.doors_after_kidnap_until_lost < 0) {
      out.doors_after_kidnap_until_lost = after_kidnap;
    }
    if (p < check_until_in && tracker.status() == TrackStatus::kTracking) {
      const TrackedPose want = truth.At(p);
      const TrackedPose got = tracker.pose();
      // Near an edge's ends the odometer error may put the pose on the neighbour.
      const double metric = truth.map().ring(want.ring).edges[want.edge].metric_in;
      if ((got.edge != want.edge || got.dir != want.dir) && want.offset_in > 8.0 &&
          want.offset_in < metric - 8.0) {
        out.pose_always_right = false;
        ADD_FAILURE() << "at travel " << p << " want edge " << want.edge << " got " << got.edge;
      }
    }
  }
  return out;
}

TEST(PoseTrackerTest, CleanWalkStaysTrackingAndFollowsTheTruthEdgeByEdge) {
  const map::Map m = TrackMap();
  const Walk truth(m, 2, +1, 40.0);
  PoseTracker tracker(m);
  const Outcome o = DriveAlong(tracker, truth.Doors(0.0, 2500.0), truth, 2400.0, Drive{});
  EXPECT_EQ(tracker.status(), TrackStatus::kTracking) << tracker.message();
  EXPECT_TRUE(o.pose_always_right);
  EXPECT_GE(o.doors_reported, 16);
  EXPECT_EQ(tracker.misses(), 0);
  EXPECT_GE(tracker.confirmations(), 2 * 16);  // every door and the wall before it
}

TEST(PoseTrackerTest, CleanWalkAgainstRingOrderWithTheOdometerCountingDown) {
  const map::Map m = TrackMap();
  const Walk truth(m, 12, -1, 30.0);  // wall 80 travelled against ring order
  PoseTracker tracker(m);
  Drive d;
  d.odometer_sign = -1;
  d.odometer_scale = 0.98;
  const Outcome o = DriveAlong(tracker, truth.Doors(0.0, 2500.0), truth, 2400.0, d);
  EXPECT_EQ(tracker.status(), TrackStatus::kTracking) << tracker.message();
  EXPECT_TRUE(o.pose_always_right);
  EXPECT_EQ(tracker.misses(), 0);
  const TrackedPose p = tracker.pose();
  EXPECT_EQ(p.dir, -1);
}

TEST(PoseTrackerTest, SingleFalseDoorIsTolerated) {
  const map::Map m = TrackMap();
  const Walk truth(m, 2, +1, 40.0);
  std::vector<PassedDoor> doors = truth.Doors(0.0, 2500.0);
  // A 36 in door seen in the middle of the 120 in wall (travel 260..380 from this start).
  doors.insert(doors.begin() + 2, PassedDoor{300.0, 336.0, map::DoorCode(DoorClass::k36)});
  PoseTracker tracker(m);
  const Outcome o = DriveAlong(tracker, doors, truth, 2400.0, Drive{});
  EXPECT_EQ(tracker.status(), TrackStatus::kTracking) << tracker.message();
  EXPECT_TRUE(o.pose_always_right);
  EXPECT_EQ(tracker.misses(), 1);
}

TEST(PoseTrackerTest, SingleMissedDoorIsTolerated) {
  const map::Map m = TrackMap();
  const Walk truth(m, 2, +1, 40.0);
  std::vector<PassedDoor> doors = truth.Doors(0.0, 2500.0);
  doors.erase(doors.begin() + 3);
  PoseTracker tracker(m);
  const Outcome o = DriveAlong(tracker, doors, truth, 2400.0, Drive{});
  EXPECT_EQ(tracker.status(), TrackStatus::kTracking) << tracker.message();
  EXPECT_TRUE(o.pose_always_right);
  EXPECT_EQ(tracker.misses(), 1);
}

TEST(PoseTrackerTest, MisSizedDoorCountsAMissButKeepsTracking) {
  const map::Map m = TrackMap();
  const Walk truth(m, 2, +1, 40.0);
  std::vector<PassedDoor> doors = truth.Doors(0.0, 2500.0);
  doors[1].code = map::DoorCode(DoorClass::k36);  // a 40 in door classified as 36
  PoseTracker tracker(m);
  const Outcome o = DriveAlong(tracker, doors, truth, 2400.0, Drive{});
  EXPECT_EQ(tracker.status(), TrackStatus::kTracking) << tracker.message();
  EXPECT_TRUE(o.pose_always_right);
  EXPECT_EQ(tracker.misses(), 1);
}

// The robot is carried, at travel 600 in, to another place of the ring; the odometer does
// not know. It must be LOST within max_consecutive_misses + 2 reported doors.
void ExpectKidnapDetected(int dir, int odometer_sign, double jump_in) {
  const map::Map m = TrackMap();
  const int start_edge = dir > 0 ? 2 : 12;
  const Walk truth(m, start_edge, dir, 30.0);
  const double kidnap_in = 600.0;
  std::vector<PassedDoor> doors = truth.Doors(0.0, kidnap_in);
  while (!doors.empty() && doors.back().far_in > kidnap_in - 10.0) doors.pop_back();
  // After the kidnap the robot meets the doors it would have met `jump_in` further on.
  for (const PassedDoor& d :
       truth.Doors(kidnap_in + jump_in + 10.0, kidnap_in + jump_in + 2000.0)) {
    doors.push_back({d.near_in - jump_in, d.far_in - jump_in, d.code});
  }
  PoseTracker tracker(m);
  Drive drive;
  drive.odometer_sign = odometer_sign;
  const Outcome o =
      DriveAlong(tracker, doors, truth, kidnap_in + 1500.0, drive, kidnap_in, kidnap_in);
  EXPECT_EQ(tracker.status(), TrackStatus::kLost) << tracker.message();
  EXPECT_GE(o.doors_after_kidnap_until_lost, 0);
  EXPECT_LE(o.doors_after_kidnap_until_lost, PoseTrackerConfig{}.max_consecutive_misses + 2)
      << tracker.message();
}

TEST(PoseTrackerTest, KidnapIsDetectedWithinAFewDoors) {
  for (double jump : {235.0, 410.0, 700.0}) {
    SCOPED_TRACE(jump);
    ExpectKidnapDetected(+1, +1, jump);
  }
}

TEST(PoseTrackerTest, KidnapIsDetectedTravellingAgainstRingOrder) {
  for (double jump : {235.0, 410.0, 700.0}) {
    SCOPED_TRACE(jump);
    ExpectKidnapDetected(-1, -1, jump);
  }
}

TEST(PoseTrackerTest, ReportsTheAnticipatedEdgeAndGrowingUncertainty) {
  const map::Map m = TrackMap();
  PoseTracker tracker(m);
  ASSERT_TRUE(tracker.Start({0, 2, +1, 40.0}, 0.0, +1));
  ASSERT_TRUE(tracker.anticipated().has_value());
  EXPECT_EQ(tracker.anticipated()->edge, 2);
  const double u0 = tracker.uncertainty_in();
  tracker.Advance(60.0);
  EXPECT_GT(tracker.uncertainty_in(), u0);
  EXPECT_EQ(tracker.pose().edge, 3);  // past the 90 in wall, 10 in into the 30 in door
  EXPECT_NEAR(tracker.pose().offset_in, 10.0, 1e-9);
}

TEST(PoseTrackerTest, PoseNotOnTheMapIsRefused) {
  const map::Map m = TrackMap();
  PoseTracker tracker(m);
  EXPECT_FALSE(tracker.Start({3, 0, +1, 0.0}, 0.0, +1));
  EXPECT_FALSE(tracker.Start({0, 99, +1, 0.0}, 0.0, +1));
  EXPECT_FALSE(tracker.Start({0, 0, 0, 0.0}, 0.0, +1));
  EXPECT_EQ(tracker.status(), TrackStatus::kIdle);
  // Edges before a start are ignored.
  tracker.OnEdge(map::SensedEdge{}, 10.0);
  EXPECT_EQ(tracker.status(), TrackStatus::kIdle);
}

}  // namespace
}  // namespace stickrep::localizer
