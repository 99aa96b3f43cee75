// The localizer process alone, fed as the landmark and locomotion processes would feed it:
// the doors of a stretch of the shipped map, seen frame by frame as the robot drives past
// them, and the odometer. It must recover the pose, and survive landmarks it cannot use.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "basePubSubTypes.h"
#include "integration/process_fixture.h"
#include "localizationPubSubTypes.h"
#include "perceptionPubSubTypes.h"
#include "runtime/process.h"
#include "runtime/system_config.h"
#include "stickrep/map.h"
#include "stickrep/map_io.h"
#include "systemPubSubTypes.h"

namespace stickrep::test {
namespace {

constexpr int kDomainId = 24;
// The stretch walked: from 20 in into wall edge 4 of wing3_corridor, forward through 30
// edges (walls and doors in turn, so that every wall is sensed as one; the 30/30 door of edge
// 13 and the 36/36 of edge 15 are what single the place out), to 36 in into the wall after
// the last door, the base driving backward: the camera looks left and a ring is listed with
// its wall on the right, so the base walks a ring in its order only backward (the localizer
// takes the direction from the odometer's sign, configs/localizer.yaml
// bayes_direction_from_travel). Every door is read with the mark the map gives it. The map's
// doors carry surveyed marks, so the localizer declares a pose at the marked model's bar (the
// posterior 0.999985, configs/localizer.yaml on_marked_maps); the 30 edges bring the right
// place over it.
constexpr char kRingId[] = "wing3_corridor";
constexpr int kStartEdge = 4;
constexpr double kStartOffsetIn = 20.0;
constexpr int kEdgesWalked = 30;
// Past the 48 in beyond a door's centre after which the localizer counts it complete
// (configs/localizer.yaml out_of_view_in), and still inside the 46 in wall that follows.
constexpr double kPastLastDoorIn = 36.0;
// One frame per 0.2 s at 2.6 ft/s, the paper's base speed.
constexpr double kFrameStepIn = 6.24;
// Frames are sent four times faster than the camera takes them: the localizer works by the
// odometer, not by the clock.
constexpr double kSendPeriodS = 0.05;
// A door is classified in the frames whose optical axis is this close to its centre (3 or
// 4 frames per door).
constexpr double kInViewIn = 12.0;
// The detector sees a double door as two leaves either side of the seam where they meet;
// their facing jambs are placed an inch apart (world::DoorFeature draws the leaves meeting
// in the middle; EdgeAssemblerConfig::leaf_gap_in).
constexpr double kStileIn = 1.0;


msgs::DoorClass ToMsg(map::DoorClass c) {
  switch (c) {
    case map::DoorClass::k30:
      return msgs::DOOR_30;
    case map::DoorClass::k32:
      return msgs::DOOR_32;
    case map::DoorClass::k36:
      return msgs::DOOR_36;
    case map::DoorClass::k40:
      return msgs::DOOR_40;
    case map::DoorClass::k30_30:
      return msgs::DOOR_30_30;
    case map::DoorClass::k36_36:
      return msgs::DOOR_36_36;
  }
  return msgs::DOOR_REJECTED;
}

// A door as the detector sees it: a single door, or one leaf of a double door, with the mark
// the map gives the door (Table 6.8), read on every leaf as the landmark process reads it.
struct Leaf {
  map::DoorClass door_class = map::DoorClass::k36;
  double width_in = 0.0;
  double centre_in = 0.0;  // along the wall from the start, in ring order
  map::DoorMark mark = map::DoorMark::kUnknown;
};

// What the landmark and locomotion processes publish while the robot drives the stretch.
struct Drive {
  std::vector<Leaf> leaves;
  double end_in = 0.0;  // along the wall from the start
  int truth_edge = 0;  // the edge the robot ends in
};

// Lays the stretch out along the wall (zero where the robot starts). Fails the test if
// the stretch is not walls and doors in turn.
Drive LayOut(const map::Ring& ring) {
  Drive drive;
  double at_in = -kStartOffsetIn;  // where the current edge starts
  double last_door_end_in = 0.0;
  for (int i = kStartEdge; i < kStartEdge + kEdgesWalked; ++i) {
    const map::Edge& e = ring.edges[i % ring.EdgeCount()];
    const bool door_expected = (i - kStartEdge) % 2 == 1;
    EXPECT_EQ(e.IsDoor(), door_expected) << "edge " << i << " of " << ring.id;
    EXPECT_TRUE(e.IsDoor() || e.IsWall()) << "edge " << i << " of " << ring.id;
    if (e.IsDoor()) {
      const map::DoorMark mark = map::DoorMarkOfPattern(e.pattern);
      if (map::IsDoubleDoor(*e.door_class)) {
        const double leaf_in = (e.metric_in - kStileIn) / 2.0;
        const map::DoorClass leaf = map::LeafClass(*e.door_class);
        drive.leaves.push_back({leaf, leaf_in, at_in + leaf_in / 2.0, mark});
        drive.leaves.push_back({leaf, leaf_in, at_in + e.metric_in - leaf_in / 2.0, mark});
      } else {
        drive.leaves.push_back({*e.door_class, e.metric_in, at_in + e.metric_in / 2.0, mark});
      }
      last_door_end_in = at_in + e.metric_in;
    }
    at_in += e.metric_in;
  }
  drive.truth_edge = (kStartEdge + kEdgesWalked) % ring.EdgeCount();
  const map::Edge& after = ring.edges[drive.truth_edge];
  EXPECT_TRUE(after.IsWall() && after.metric_in > kPastLastDoorIn)
      << "the stretch must end in a wall longer than " << kPastLastDoorIn << " in";
  drive.end_in = last_door_end_in + kPastLastDoorIn;
  return drive;
}

class LocalizerProcessTest : public ProcessFixture {
 protected:
  LocalizerProcessTest()
      : ProcessFixture(kDomainId),
        system_(runtime::SystemConfig::LoadFile(ConfigPath("system.yaml"))),
        landmarks_(participant(), "perception/landmark"),
        odometry_(participant(), "robot/odometry"),
        poses_(participant(), executor(), "localization/pose",
               [this](const msgs::LocalizationPose& p) {
                 last_pose_ = p;
                 poses_received_++;
               }),
        status_(participant(), executor(), "system/status", [this](const msgs::ComponentStatus& s) {
          if (s.component_name() == "localizer") last_status_ = s;
        }) {}

  // Starts the localizer on the same system file the test reads the map from, and waits for
  // its first pose and for both input streams to be matched.
  void StartLocalizer() {
    localizer_ = &Start("stickrep-localizer", {"--system", system_.file});
    ASSERT_TRUE(SpinUntil(
        [&] {
          if (localizer_->Exited()) return true;
          return poses_received_ > 0 && landmarks_.counters().matched > 0 &&
                 odometry_.counters().matched > 0;
        },
        30.0))
        << Outputs();
    ASSERT_FALSE(localizer_->Exited()) << Outputs();
  }

  void PublishOdometry(double odometer_in) {
    msgs::Odometry o;
    o.distance_in(odometer_in);
    o.pose().x_in(odometer_in);
    o.linear_speed_ftps(-kFrameStepIn / 12.0 / 0.2);
    odometry_.Publish(o, runtime::WallClockNowNs());
  }

  // One classified door in the frame taken at `odometer_in`, as the landmark process
  // reports it.
  void PublishLandmark(msgs::DoorClass door_class, double width_in, double odometer_in,
                       double centre_in, map::DoorMark mark = map::DoorMark::kUnknown) {
    msgs::LandmarkObservation o;
    o.door_class(door_class);
    o.mark(static_cast<msgs::DoorMark>(mark));
    o.width_in(width_in);
    o.confidence(0.9);
    o.range_in(72.0);
    o.in_envelope(true);
    o.odometry_distance_in(odometer_in);
    o.center_offset_in(centre_in - odometer_in);
    const int64_t now_ns = runtime::WallClockNowNs();
    o.image_stamp_ns(now_ns);
    landmarks_.Publish(o, now_ns);
  }

  runtime::SystemConfig system_;
  runtime::Writer<msgs::LandmarkObservationPubSubType> landmarks_;
  runtime::Writer<msgs::OdometryPubSubType> odometry_;
  msgs::LocalizationPose last_pose_;
  int poses_received_ = 0;
  msgs::ComponentStatus last_status_;
  launch::ChildProcess* localizer_ = nullptr;

 private:
  runtime::Reader<msgs::LocalizationPosePubSubType> poses_;
  runtime::Reader<msgs::ComponentStatusPubSubType> status_;
};

TEST_F(LocalizerProcessTest, ReachesLocalizedOnTheTrueEdgeFromTheDoorsOfAStretchOfTheMap) {
  const map::Map building = map::LoadMap(system_.map_file);
  const int ring_index = building.FindRing(kRingId);
  ASSERT_GE(ring_index, 0) << kRingId << " is not in " << system_.map_file;
  const Drive drive = LayOut(building.ring(ring_index));
  ASSERT_FALSE(::testing::Test::HasFailure());
  StartLocalizer();

  // One frame per tick: the doors in view, then the odometer of that instant. Driving
  // backward, the odometer runs down as the robot goes along the wall.
  int frame = 0;
  bool driving = true;
  executor().AddTimer(kSendPeriodS, [&] {
    if (!driving) return;
    const double along_in = frame++ * kFrameStepIn;
    if (along_in > drive.end_in) {
      driving = false;
      return;
    }
    for (const Leaf& leaf : drive.leaves) {
      if (std::abs(leaf.centre_in - along_in) <= kInViewIn) {
        PublishLandmark(ToMsg(leaf.door_class), leaf.width_in, -along_in, -leaf.centre_in,
                        leaf.mark);
      }
    }
    PublishOdometry(-along_in);
  });

  // Once the last door is behind the robot the pose must be the true one: one candidate, on
  // the edge the robot is in, travelling in ring order.
  auto on_truth = [&] {
    return last_pose_.status() == msgs::LOCALIZATION_LOCALIZED &&
           last_pose_.candidate_count() == 1 && last_pose_.best().ring_id() == kRingId &&
           last_pose_.best().edge_index() == static_cast<uint32_t>(drive.truth_edge) &&
           last_pose_.best().forward();
  };
  const bool localized = SpinUntil([&] { return !driving && on_truth(); }, 30.0);
  EXPECT_FALSE(driving) << "frame " << frame << " of the stretch after 30 s";
  EXPECT_TRUE(localized) << "expected LOCALIZED with 1 candidate at " << kRingId << " edge "
                         << drive.truth_edge << " forward; got status " << last_pose_.status()
                         << " with " << last_pose_.candidate_count() << " candidates, best "
                         << last_pose_.best().ring_id() << " edge "
                         << last_pose_.best().edge_index()
                         << (last_pose_.best().forward() ? " forward" : " backward") << " ("
                         << last_pose_.edges_sensed() << " edges sensed, '" << last_pose_.message()
                         << "')\n"
                         << Outputs();
  StopAllAndExpectCleanExit();
}

TEST_F(LocalizerProcessTest, DropsALandmarkWithANanWidthAndARejectedOneAndKeepsRunning) {
  StartLocalizer();
  ASSERT_TRUE(SpinUntil([&] { return last_status_.state() == msgs::COMPONENT_ACTIVE; }, 10.0));
  const uint64_t dropped_before = last_status_.samples_dropped();

  PublishOdometry(0.0);
  PublishLandmark(msgs::DOOR_36, std::numeric_limits<double>::quiet_NaN(), 0.0, 4.0);
  PublishLandmark(msgs::DOOR_REJECTED, 36.0, 0.0, 4.0);

  ASSERT_TRUE(SpinUntil(
      [&] { return last_status_.samples_dropped() >= dropped_before + 2 || localizer_->Exited(); },
      10.0))
      << "dropped " << last_status_.samples_dropped() - dropped_before << "\n"
      << Outputs();
  ASSERT_FALSE(localizer_->Exited()) << Outputs();
  // Still publishing its pose, with nothing taken from those landmarks.
  const int poses_before = poses_received_;
  ASSERT_TRUE(SpinUntil([&] { return poses_received_ > poses_before; }, 5.0)) << Outputs();
  EXPECT_EQ(last_pose_.edges_sensed(), 0u);
  StopAllAndExpectCleanExit();
}

}  // namespace
}  // namespace stickrep::test
