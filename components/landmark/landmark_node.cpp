#include "landmark/landmark_node.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <deque>

#include "basePubSubTypes.h"
#include "landmark/landmark_config.h"
#include "landmark/landmark_pipeline.h"
#include "landmark/odometer_history.h"
#include "perceptionPubSubTypes.h"
#include "runtime/endpoint.h"
#include "runtime/latency.h"
#include "sensorsPubSubTypes.h"

namespace stickrep::landmark {

namespace {

msgs::DoorClass ToMsg(sensing::DoorClass c) {
  switch (c) {
    case sensing::DoorClass::kDoor30: return msgs::DOOR_30;
    case sensing::DoorClass::kDoor32: return msgs::DOOR_32;
    case sensing::DoorClass::kDoor36: return msgs::DOOR_36;
    case sensing::DoorClass::kDoor40: return msgs::DOOR_40;
    case sensing::DoorClass::kDouble30: return msgs::DOOR_30_30;
    case sensing::DoorClass::kDouble36: return msgs::DOOR_36_36;
  }
  return msgs::DOOR_REJECTED;
}

class LandmarkNode : public runtime::ProcessNode {
 public:
  void Configure(runtime::NodeContext& ctx) override {
    ctx_ = &ctx;
    const LandmarkConfig config = LoadLandmarkConfig(ctx.config);
    max_scan_age_ns_ = static_cast<int64_t>(config.max_scan_age_s * 1e9);
    robot_ = sensing::LoadRobotConfigFile(ctx.system.robot_file);
    pipeline_ = std::make_unique<LandmarkPipeline>(robot_, config.detector, config.estimator);

    writer_ = std::make_unique<runtime::Writer<msgs::LandmarkObservationPubSubType>>(
        ctx.participant, "perception/landmark");
    scans_ = std::make_unique<runtime::Reader<msgs::SonarScanPubSubType>>(
        ctx.participant, ctx.executor, "robot/sonar",
        [this](const msgs::SonarScan& s) { OnScan(s); });
    odometry_ = std::make_unique<runtime::Reader<msgs::OdometryPubSubType>>(
        ctx.participant, ctx.executor, "robot/odometry",
        [this](const msgs::Odometry& o) { OnOdometry(o); });
    images_ = std::make_unique<runtime::Reader<msgs::ImagePubSubType>>(
        ctx.participant, ctx.executor, "robot/camera/image",
        [this](const msgs::Image& m) { OnImage(m); });
  }

  std::string Summary() const override {
    return fmt::format("{} frames processed, {} doors observed, {} frames without a door, {} "
                       "frames of the camera never seen; camera frame to observation {}",
                       frames_, doors_, no_door_, frames_missed_, latency_.Summary());
  }

 private:
  void OnScan(const msgs::SonarScan& s) {
    ctx_->counters.CountIn();
    sensing::SonarScan scan;
    for (size_t k = 0; k < s.range_in().size(); ++k) {
      const double r = s.range_in()[k];
      const bool valid = s.reading_state()[k] == msgs::SONAR_VALID;
      if (valid && (!std::isfinite(r) || r <= 0.0)) {
        ctx_->counters.Drop("robot/sonar", "a reading marked valid is not a positive range");
        return;
      }
      scan.ranges_in.push_back(r);
      scan.valid.push_back(valid);
    }
    scans_by_time_.push_back({s.header().stamp_ns(), std::move(scan)});
    if (scans_by_time_.size() > kScanHistory) scans_by_time_.pop_front();
    ProcessReadyFrames();
  }

  void OnOdometry(const msgs::Odometry& o) {
    ctx_->counters.CountIn();
    if (!std::isfinite(o.distance_in())) {
      ctx_->counters.Drop("robot/odometry", "non-finite distance");
      return;
    }
    if (!odometer_.Add(o.header().stamp_ns(), o.distance_in())) {
      ctx_->counters.Drop("robot/odometry", "time went backwards");
      return;
    }
    last_odometry_ns_ = o.header().stamp_ns();
    ProcessReadyFrames();
  }

  // Frames wait until the scan and the odometry of their own instant have arrived (or can
  // no longer arrive), so that a frame is paired by time, not by which stream came first:
  // the same recording replayed gives the same observations.
  void OnImage(const msgs::Image& m) {
    ctx_->counters.CountIn();
    // Frames the camera wrote that never arrived: superseded in the keep-last-1 stream while
    // this process was busy (or lost on the way).
    const uint32_t seq = m.header().sequence_number();
    if (last_image_seq_ > 0 && seq > last_image_seq_ + 1) frames_missed_ += seq - last_image_seq_ - 1;
    last_image_seq_ = std::max(last_image_seq_, seq);
    pending_.push_back({m, images_->source_timestamp_ns()});
    if (pending_.size() > kMaxPendingFrames) {
      Process(pending_.front());  // the oldest with what has come: never hold more
      pending_.pop_front();
    }
    ProcessReadyFrames();
  }

  void ProcessReadyFrames() {
    while (!pending_.empty()) {
      const int64_t t = pending_.front().image.header().stamp_ns();
      const int64_t newest_scan = scans_by_time_.empty() ? 0 : scans_by_time_.back().stamp_ns;
      const bool scans_done = newest_scan >= t;
      const bool odometry_done = last_odometry_ns_ >= t;
      // Data newer than the frame by more than the pairing window: what is missing is lost.
      const int64_t newest = std::max(newest_scan, last_odometry_ns_);
      if (!(scans_done && odometry_done) && newest - t <= max_scan_age_ns_) return;
      Process(pending_.front());
      pending_.pop_front();
    }
  }

  // The scan nearest the frame in time, within the pairing window.
  const sensing::SonarScan* ScanAt(int64_t stamp_ns) const {
    const TimedScan* best = nullptr;
    for (const TimedScan& s : scans_by_time_) {
      if (best == nullptr || std::llabs(s.stamp_ns - stamp_ns) < std::llabs(best->stamp_ns - stamp_ns)) {
        best = &s;
      }
    }
    if (best == nullptr || std::llabs(best->stamp_ns - stamp_ns) > max_scan_age_ns_) return nullptr;
    return &best->scan;
  }

  struct PendingFrame {
    msgs::Image image;
    int64_t source_timestamp_ns = 0;
  };

  void Process(const PendingFrame& frame) {
    const msgs::Image& m = frame.image;
    const sensing::SonarScan* scan = ScanAt(m.header().stamp_ns());
    if (scan == nullptr) {
      ctx_->counters.Drop("robot/camera/image", "no sonar scan near the frame in time");
      return;
    }
    const std::optional<double> odometer_in = odometer_.At(m.header().stamp_ns(), max_scan_age_ns_);
    if (!odometer_in) {
      ctx_->counters.Drop("robot/camera/image", "no odometry near the frame in time");
      return;
    }
    frames_++;
    const vision::ImageView view{static_cast<int>(m.width_px()), static_cast<int>(m.height_px()),
                                 static_cast<int>(m.step_bytes()), m.encoding(), m.data().data(),
                                 m.data().size()};
    const FrameOutcome out = pipeline_->Process(view, *scan);
    switch (out.kind) {
      case FrameOutcome::Kind::kBadFrame:
      case FrameOutcome::Kind::kNoRange:
        ctx_->counters.Drop("robot/camera/image", out.reason);
        return;
      case FrameOutcome::Kind::kNoDoor:
        no_door_++;
        return;
      case FrameOutcome::Kind::kObservation:
        break;
    }
    const sensing::LandmarkObservation& o = out.observation;
    msgs::LandmarkObservation msg;
    msg.door_class(ToMsg(o.door_class));
    msg.width_in(o.width_in);
    msg.confidence(o.confidence);
    msg.left_jamb_px(o.footprints.lj_px);
    msg.right_jamb_px(o.footprints.rj_px);
    msg.range_in(o.range_in);
    msg.center_offset_in(out.center_offset_in);
    msg.look_angle_rad(o.look_angle_rad);
    msg.in_envelope(o.in_envelope);
    msg.odometry_distance_in(*odometer_in);
    msg.image_stamp_ns(m.header().stamp_ns());
    if (writer_->Publish(msg, m.header().stamp_ns())) {
      ctx_->counters.CountOut();
      doors_++;
      // Wall clock from the camera process writing the frame to the observation written.
      latency_.Add((ctx_->now_ns() - frame.source_timestamp_ns) * 1e-6);
    }
  }

  runtime::NodeContext* ctx_ = nullptr;
  sensing::RobotConfig robot_;
  std::unique_ptr<LandmarkPipeline> pipeline_;
  int64_t max_scan_age_ns_ = 300000000;
  struct TimedScan {
    int64_t stamp_ns = 0;
    sensing::SonarScan scan;
  };
  static constexpr size_t kScanHistory = 16;
  static constexpr size_t kMaxPendingFrames = 8;
  std::deque<TimedScan> scans_by_time_;
  std::deque<PendingFrame> pending_;
  int64_t last_odometry_ns_ = 0;
  OdometerHistory odometer_;
  uint64_t frames_ = 0, doors_ = 0, no_door_ = 0;
  runtime::LatencyLog latency_;
  uint32_t last_image_seq_ = 0;
  uint64_t frames_missed_ = 0;
  std::unique_ptr<runtime::Writer<msgs::LandmarkObservationPubSubType>> writer_;
  std::unique_ptr<runtime::Reader<msgs::SonarScanPubSubType>> scans_;
  std::unique_ptr<runtime::Reader<msgs::OdometryPubSubType>> odometry_;
  std::unique_ptr<runtime::Reader<msgs::ImagePubSubType>> images_;
};

}  // namespace

std::unique_ptr<runtime::ProcessNode> MakeLandmarkNode() { return std::make_unique<LandmarkNode>(); }

}  // namespace stickrep::landmark
