#pragma once

#include <cstdint>
#include <deque>
#include <memory>

#include "component/component.h"
#include "landmark/landmark_config.h"
#include "landmark/landmark_pipeline.h"
#include "landmark/odometer_history.h"
#include "messages/messages.h"
#include "sensing/robot_config.h"

namespace stickrep::landmark {

// The landmark process's logic: pairs each camera frame with the sonar scan taken nearest to
// it and the odometer interpolated at its instant, runs the landmark pipeline and publishes
// classified doors on perception/landmark with the odometry distance at which they were seen.
// Frames wait until the scan and odometry of their own instant have arrived (or can no longer
// arrive), so a frame is paired by time, not by which stream came first.
class LandmarkComponent : public component::Component {
 public:
  LandmarkComponent(component::Context& ctx, const sensing::RobotConfig& robot,
                    const LandmarkConfig& config,
                    component::Publisher<message::LandmarkObservation>& observations);

  void OnScan(const message::SonarScan& scan);
  void OnOdometry(const message::Odometry& odometry);
  void OnImage(const message::Image& image);
  std::string Summary() const override;

  uint64_t doors_observed() const { return doors_; }
  uint64_t frames_processed() const { return frames_; }

 private:
  struct TimedScan {
    int64_t stamp_ns = 0;
    sensing::SonarScan scan;
  };
  void ProcessReadyFrames();
  void Process(const message::Image& image);
  const sensing::SonarScan* ScanAt(int64_t stamp_ns) const;

  static constexpr size_t kScanHistory = 16;
  static constexpr size_t kMaxPendingFrames = 8;
  component::Context& ctx_;
  LandmarkPipeline pipeline_;
  component::Publisher<message::LandmarkObservation>& observations_;
  int64_t max_scan_age_ns_;
  std::deque<TimedScan> scans_by_time_;
  std::deque<message::Image> pending_;
  int64_t last_odometry_ns_ = 0;
  OdometerHistory odometer_;
  uint64_t frames_ = 0, doors_ = 0, no_door_ = 0;
  uint32_t last_image_seq_ = 0;
  uint64_t frames_missed_ = 0;
};

// The scan as the landmark pipeline reads it: ranges with a valid flag.
sensing::SonarScan ToPipelineScan(const message::SonarScan& scan);

}  // namespace stickrep::landmark
