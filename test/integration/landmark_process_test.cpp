// The landmark process alone, fed as the sonar, camera and locomotion processes would feed
// it: frames and sonar scans rendered by the simulated world from the same pose, and the
// odometer. It must classify a closed 36 in door, stay silent before a blank wall, and
// survive malformed samples.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "basePubSubTypes.h"
#include "common/units.h"
#include "integration/process_fixture.h"
#include "perceptionPubSubTypes.h"
#include "runtime/process.h"
#include "sensorsPubSubTypes.h"
#include "systemPubSubTypes.h"
#include "world/camera_renderer.h"
#include "world/robot_models.h"
#include "world/scene.h"
#include "world/sonar_ring.h"
#include "world/world.h"

namespace stickrep::test {
namespace {

constexpr int kDomainId = 23;
constexpr double kDoorStartIn = 120.0;
constexpr double kDoorWidthIn = 36.0;
constexpr double kHallwayWidthIn = 144.0;  // the robot in the middle is 6 ft from the doors
constexpr double kRangeIn = 72.0;
// One frame per 0.2 s at 2.6 ft/s (the paper's base speed) moves the robot 6.24 in.
constexpr double kFrameStepIn = 6.24;
constexpr double kFramePeriodS = 0.2;
constexpr std::uint64_t kSeed = 20261123;


// One frame as the landmark process receives it: the image and the gated sonar scan taken
// from the same pose.
struct Frame {
  msgs::Image image;
  msgs::SonarScan scan;
  double along_in = 0.0;  // optical axis past the door centre, along the wall
};

// Renders frames of a straight hallway with the robot description of configs/robot.yaml.
class FrameRenderer {
 public:
  FrameRenderer()
      : models_(world::LoadRobotModels(ConfigPath("robot.yaml"))),
        camera_(models_.camera),
        ring_(models_.sonar),
        footprint_rad_(DegToRad(15.0)),
        rng_(kSeed) {}

  // The robot travels along +x in the middle of the hallway, the camera looking sideways at
  // the feature wall kRangeIn away, its optical axis meeting the wall at `axis_x_in`.
  Frame Render(const world::Scene& scene, double axis_x_in) {
    const world::Pose2d X_WR{axis_x_in, kHallwayWidthIn / 2.0 - kRangeIn, 0.0};
    const world::RenderedFrame rendered = camera_.Render(scene, X_WR, world::Illumination{}, rng_);
    Frame f;
    f.image.width_px(static_cast<uint32_t>(rendered.image.cols));
    f.image.height_px(static_cast<uint32_t>(rendered.image.rows));
    f.image.encoding("mono8");
    f.image.step_bytes(static_cast<uint32_t>(rendered.image.cols));
    for (int row = 0; row < rendered.image.rows; ++row) {
      const uint8_t* p = rendered.image.ptr<uint8_t>(row);
      f.image.data().insert(f.image.data().end(), p, p + rendered.image.cols);
    }
    // Gated as the sonar process gates: no echo, and echoes outside the accurate footprint
    // of §4.3 (incidence above 15°), are not valid.
    const std::vector<world::SonarReading> readings = ring_.SenseExact(scene, X_WR);
    uint16_t valid = 0;
    for (size_t k = 0; k < readings.size() && k < f.scan.range_in().size(); ++k) {
      const world::SonarReading& r = readings[k];
      f.scan.range_in()[k] = r.valid ? static_cast<float>(r.range_in) : 0.0f;
      f.scan.reading_state()[k] = !r.valid                           ? msgs::SONAR_NO_ECHO
                                  : r.incidence_rad > footprint_rad_ ? msgs::SONAR_OUTSIDE_FOOTPRINT
                                                                     : msgs::SONAR_VALID;
      valid += f.scan.reading_state()[k] == msgs::SONAR_VALID;
    }
    f.scan.valid_count(valid);
    return f;
  }

 private:
  world::RobotModels models_;
  world::CameraRenderer camera_;
  world::SonarRingSimulator ring_;
  double footprint_rad_;
  std::mt19937_64 rng_;
};

world::HallwayOptions Hallway() {
  world::HallwayOptions options;
  options.width_in = kHallwayWidthIn;
  return options;
}

// Four frames of a closed 36 in door, 6.24 in apart as the robot passes it.
std::vector<Frame> DoorFrames(FrameRenderer& renderer) {
  const world::Scene scene(world::MakeStraightHallway(
      {world::HallwayFeature::Wall(kDoorStartIn), world::HallwayFeature::Door(kDoorWidthIn),
       world::HallwayFeature::Wall(240.0)},
      Hallway()));
  const double centre_x_in = kDoorStartIn + kDoorWidthIn / 2.0;
  std::vector<Frame> frames;
  for (double along_in : {-1.5, -0.5, 0.5, 1.5}) {
    along_in *= kFrameStepIn;
    frames.push_back(renderer.Render(scene, centre_x_in + along_in));
    frames.back().along_in = along_in;
  }
  return frames;
}

// Four frames of a plain wall.
std::vector<Frame> BlankWallFrames(FrameRenderer& renderer) {
  const world::Scene scene(
      world::MakeStraightHallway({world::HallwayFeature::Wall(600.0)}, Hallway()));
  std::vector<Frame> frames;
  for (int i = 0; i < 4; ++i) {
    frames.push_back(renderer.Render(scene, 300.0 + i * kFrameStepIn));
  }
  return frames;
}

class LandmarkProcessTest : public ProcessFixture {
 protected:
  LandmarkProcessTest()
      : ProcessFixture(kDomainId),
        scans_(participant(), "robot/sonar"),
        odometry_(participant(), "robot/odometry"),
        images_(participant(), "robot/camera/image"),
        landmarks_(participant(), executor(), "perception/landmark",
                   [this](const msgs::LandmarkObservation& o) { observations_.push_back(o); }),
        status_(participant(), executor(), "system/status", [this](const msgs::ComponentStatus& s) {
          if (s.component_name() == "landmark") last_status_ = s;
        }) {
    FrameRenderer renderer;
    door_frames_ = DoorFrames(renderer);
    blank_frames_ = BlankWallFrames(renderer);
    // A stream of frames, one per 0.2 s as the camera sends them: Send() queues, the timer
    // publishes on the test's executor while SpinUntil waits.
    executor().AddTimer(kFramePeriodS, [this] { PublishNext(); });
  }

  // Starts the landmark process and waits until it is active and every stream is matched.
  void StartLandmark() {
    landmark_ = &Start("stickrep-landmark");
    ASSERT_TRUE(SpinUntil(
        [&] {
          if (landmark_->Exited()) return true;
          return last_status_.state() == msgs::COMPONENT_ACTIVE && scans_.counters().matched > 0 &&
                 odometry_.counters().matched > 0 && images_.counters().matched > 0 &&
                 landmarks_.counters().matched > 0;
        },
        30.0))
        << Outputs();
    ASSERT_FALSE(landmark_->Exited()) << Outputs();
  }

  // Sends door frames, one per tick, until an image sent from now on has been classified;
  // returns that observation. Used first to know that the streams flow both ways (matching
  // on our side does not mean the process has matched us yet), then to see that the
  // process still works.
  msgs::LandmarkObservation SendDoorFramesUntilOneIsClassified() {
    const size_t first = sent_image_stamps_.size();
    std::optional<msgs::LandmarkObservation> found;
    sending_door_frames_ = true;
    const bool ok = SpinUntil(
        [&] {
          const std::set<int64_t> stamps(sent_image_stamps_.begin() + first,
                                         sent_image_stamps_.end());
          for (const auto& o : observations_) {
            if (stamps.count(o.image_stamp_ns())) found = o;
          }
          return found.has_value();
        },
        30.0);
    sending_door_frames_ = false;
    EXPECT_TRUE(ok) << "no door frame was classified\n" << Outputs();
    EXPECT_TRUE(SpinUntil([&] { return queue_.empty(); }, 5.0));
    return found.value_or(msgs::LandmarkObservation{});
  }

  // True once everything queued has been published.
  bool AllSent() const { return queue_.empty(); }

  // Queues a frame: its scan, odometry and image go out together at the next tick.
  void Send(const Frame& f) { queue_.push_back(Item{f, true, true}); }
  // Queues a scan and odometry with no image.
  void SendScanOnly(const Frame& f) { queue_.push_back(Item{f, true, false}); }

  // Stamps of the images sent so far, in order.
  const std::vector<int64_t>& sent_image_stamps() const { return sent_image_stamps_; }
  // Observations made from images with these stamps.
  std::vector<msgs::LandmarkObservation> ObservationsOf(const std::set<int64_t>& stamps) const {
    std::vector<msgs::LandmarkObservation> out;
    for (const auto& o : observations_) {
      if (stamps.count(o.image_stamp_ns())) out.push_back(o);
    }
    return out;
  }

  std::vector<Frame> door_frames_;
  std::vector<Frame> blank_frames_;
  std::vector<msgs::LandmarkObservation> observations_;
  msgs::ComponentStatus last_status_;
  launch::ChildProcess* landmark_ = nullptr;
  // While set, door frames are sent whenever the queue is empty.
  bool sending_door_frames_ = false;
  // Along-wall offset of the door centre from the optical axis by image stamp, for the
  // door frames.
  std::map<int64_t, double> door_centre_offset_by_stamp_;
  std::map<int64_t, double> odometer_by_stamp_;

 private:
  struct Item {
    Frame frame;
    bool scan = true;
    bool image = true;
  };

  void PublishNext() {
    if (queue_.empty() && sending_door_frames_) {
      Send(door_frames_[next_door_frame_++ % door_frames_.size()]);
    }
    if (queue_.empty()) return;
    Item item = std::move(queue_.front());
    queue_.erase(queue_.begin());
    const int64_t stamp_ns = runtime::WallClockNowNs();
    // The base moves on at a steady speed whatever the scene in view.
    odometer_in_ += kFrameStepIn;
    if (item.scan) {
      msgs::Odometry odometry;
      odometry.distance_in(odometer_in_);
      odometry.pose().x_in(odometer_in_);
      odometry.linear_speed_ftps(kFrameStepIn / 12.0 / kFramePeriodS);
      // The sonar and odometry of a frame's instant reach the process before the frame
      // itself, as they would from the device processes.
      scans_.Publish(item.frame.scan, stamp_ns);
      odometry_.Publish(odometry, stamp_ns);
    }
    if (item.image) {
      images_.Publish(item.frame.image, stamp_ns);
      sent_image_stamps_.push_back(stamp_ns);
      odometer_by_stamp_[stamp_ns] = odometer_in_;
      door_centre_offset_by_stamp_[stamp_ns] = -item.frame.along_in;
    }
  }

  runtime::Writer<msgs::SonarScanPubSubType> scans_;
  runtime::Writer<msgs::OdometryPubSubType> odometry_;
  runtime::Writer<msgs::ImagePubSubType> images_;
  runtime::Reader<msgs::LandmarkObservationPubSubType> landmarks_;
  runtime::Reader<msgs::ComponentStatusPubSubType> status_;
  std::vector<Item> queue_;
  std::vector<int64_t> sent_image_stamps_;
  size_t next_door_frame_ = 0;
  double odometer_in_ = 0.0;  // zero where the robot was switched on
};

TEST_F(LandmarkProcessTest, ClassifiesEveryFrameOfAClosed36InDoorAtSixFeetAsDoor36) {
  StartLandmark();
  SendDoorFramesUntilOneIsClassified();

  // One frame at a time: the camera stream keeps only the newest frame, so a frame sent
  // while the process is still busy with the previous one would replace it.
  std::set<int64_t> stamps;
  for (const Frame& f : door_frames_) {
    const size_t index = sent_image_stamps().size();
    Send(f);
    ASSERT_TRUE(SpinUntil(
        [&] {
          return sent_image_stamps().size() > index &&
                 ObservationsOf({sent_image_stamps()[index]}).size() == 1;
        },
        20.0))
        << "no observation of door frame " << stamps.size() << "\n"
        << Outputs();
    stamps.insert(sent_image_stamps()[index]);
  }
  ASSERT_EQ(ObservationsOf(stamps).size(), door_frames_.size());

  for (const msgs::LandmarkObservation& o : ObservationsOf(stamps)) {
    EXPECT_EQ(o.door_class(), msgs::DOOR_36) << "width " << o.width_in() << " in";
    EXPECT_NEAR(o.width_in(), kDoorWidthIn, 3.0);
    EXPECT_NEAR(o.range_in(), kRangeIn, 3.0);
    // The localizer places the door at odometer + offset: both must be the frame's. A frame
    // that beats its own odometry sample is placed by the last speed carried on, which may
    // differ by a rounding of the sample times (well under the 0.6 in of jamb placement).
    EXPECT_NEAR(o.odometry_distance_in(), odometer_by_stamp_.at(o.image_stamp_ns()), 0.1);
    EXPECT_NEAR(o.center_offset_in(), door_centre_offset_by_stamp_.at(o.image_stamp_ns()), 3.0)
        << "door centre along the wall from the optical axis, positive toward the base's forward";
  }
  StopAllAndExpectCleanExit();
}

TEST_F(LandmarkProcessTest, PublishesNoObservationForFramesOfABlankWall) {
  StartLandmark();
  SendDoorFramesUntilOneIsClassified();
  // The counters of a heartbeat sent after that observation.
  ASSERT_TRUE(SpinUntil([&] { return last_status_.samples_out() > 0; }, 5.0));
  const uint64_t in_before = last_status_.samples_in();
  const uint64_t dropped_before = last_status_.samples_dropped();

  // Blank-wall frames, then door frames: once a door frame's observation is in, every blank
  // frame before it has been through the detector (the samples of one writer arrive in
  // order, and the process handles them in order).
  const size_t first = sent_image_stamps().size();
  for (int pass = 0; pass < 2; ++pass) {
    for (const Frame& f : blank_frames_) Send(f);
  }
  const size_t blank_count = 2 * blank_frames_.size();
  SendDoorFramesUntilOneIsClassified();
  ASSERT_GE(sent_image_stamps().size(), first + blank_count);
  const std::set<int64_t> blank(sent_image_stamps().begin() + first,
                                sent_image_stamps().begin() + first + blank_count);
  for (const msgs::LandmarkObservation& o : ObservationsOf(blank)) {
    ADD_FAILURE() << "a blank wall gave a door: class " << o.door_class() << ", width "
                  << o.width_in() << " in, range " << o.range_in() << " in";
  }
  // And the blank frames were looked at: they all arrived (scan, odometry and image each) and
  // none was dropped for want of a scan or odometry near it.
  ASSERT_TRUE(
      SpinUntil([&] { return last_status_.samples_in() >= in_before + 3 * blank_count; }, 5.0))
      << "samples in " << last_status_.samples_in() - in_before << "\n"
      << Outputs();
  EXPECT_EQ(last_status_.samples_dropped(), dropped_before) << Outputs();
  StopAllAndExpectCleanExit();
}

TEST_F(LandmarkProcessTest, DropsAMalformedImageAndANanRangeAndClassifiesTheNextGoodFrame) {
  StartLandmark();
  SendDoorFramesUntilOneIsClassified();
  // The counters of a heartbeat sent after that observation.
  ASSERT_TRUE(SpinUntil([&] { return last_status_.samples_out() > 0; }, 5.0));
  const uint64_t dropped_before = last_status_.samples_dropped();

  // An image whose data is shorter than width x height, with a good scan and odometry.
  Frame short_image = door_frames_[0];
  short_image.image.data().resize(short_image.image.data().size() - 1000);
  Send(short_image);
  // A scan whose coaxial reading is NaN yet marked valid.
  Frame nan_range = door_frames_[1];
  nan_range.scan.range_in()[0] = std::numeric_limits<float>::quiet_NaN();
  nan_range.scan.reading_state()[0] = msgs::SONAR_VALID;
  SendScanOnly(nan_range);
  const size_t bad_image = sent_image_stamps().size();
  ASSERT_TRUE(SpinUntil([&] { return AllSent(); }, 5.0));
  ASSERT_EQ(sent_image_stamps().size(), bad_image + 1);

  // Both are dropped and counted (the heartbeat carries the count), and the process runs on.
  ASSERT_TRUE(SpinUntil(
      [&] { return last_status_.samples_dropped() >= dropped_before + 2 || landmark_->Exited(); },
      10.0))
      << "dropped " << last_status_.samples_dropped() - dropped_before << "\n"
      << Outputs();
  ASSERT_FALSE(landmark_->Exited()) << Outputs();
  EXPECT_TRUE(ObservationsOf({sent_image_stamps()[bad_image]}).empty());

  const msgs::LandmarkObservation next = SendDoorFramesUntilOneIsClassified();
  EXPECT_EQ(next.door_class(), msgs::DOOR_36) << "width " << next.width_in() << " in";
  StopAllAndExpectCleanExit();
}

}  // namespace
}  // namespace stickrep::test
