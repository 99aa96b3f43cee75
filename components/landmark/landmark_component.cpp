#include "landmark/landmark_component.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>

namespace stickrep::landmark {

sensing::SonarScan ToPipelineScan(const message::SonarScan& scan) {
  sensing::SonarScan s;
  for (size_t k = 0; k < scan.range_in.size(); ++k) {
    s.ranges_in.push_back(scan.range_in[k]);
    s.valid.push_back(scan.state[k] == sonar::ReadingState::kValid);
  }
  return s;
}

LandmarkComponent::LandmarkComponent(
    component::Context& ctx, const sensing::RobotConfig& robot, const LandmarkConfig& config,
    component::Publisher<message::LandmarkObservation>& observations)
    : ctx_(ctx),
      pipeline_(robot, config.detector, config.estimator),
      observations_(observations),
      max_scan_age_ns_(static_cast<int64_t>(config.max_scan_age_s * 1e9)) {}

void LandmarkComponent::OnScan(const message::SonarScan& scan) {
  scans_by_time_.push_back({scan.header.stamp_ns, ToPipelineScan(scan)});
  if (scans_by_time_.size() > kScanHistory) scans_by_time_.pop_front();
  ProcessReadyFrames();
}

void LandmarkComponent::OnOdometry(const message::Odometry& odometry) {
  if (!odometer_.Add(odometry.header.stamp_ns, odometry.distance_in)) {
    ctx_.counters.Drop("robot/odometry", "time went backwards");
    return;
  }
  last_odometry_ns_ = odometry.header.stamp_ns;
  ProcessReadyFrames();
}

void LandmarkComponent::OnImage(const message::Image& image) {
  // Frames the camera wrote that never arrived: superseded in the keep-last-1 stream while
  // this process was busy (or lost on the way).
  const uint32_t seq = image.header.sequence;
  if (last_image_seq_ > 0 && seq > last_image_seq_ + 1) frames_missed_ += seq - last_image_seq_ - 1;
  last_image_seq_ = std::max(last_image_seq_, seq);
  pending_.push_back(image);
  if (pending_.size() > kMaxPendingFrames) {
    Process(pending_.front());  // the oldest with what has come: never hold more
    pending_.pop_front();
  }
  ProcessReadyFrames();
}

void LandmarkComponent::ProcessReadyFrames() {
  while (!pending_.empty()) {
    const int64_t t = pending_.front().header.stamp_ns;
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

const sensing::SonarScan* LandmarkComponent::ScanAt(int64_t stamp_ns) const {
  const TimedScan* best = nullptr;
  for (const TimedScan& s : scans_by_time_) {
    if (best == nullptr ||
        std::llabs(s.stamp_ns - stamp_ns) < std::llabs(best->stamp_ns - stamp_ns)) {
      best = &s;
    }
  }
  if (best == nullptr || std::llabs(best->stamp_ns - stamp_ns) > max_scan_age_ns_) return nullptr;
  return &best->scan;
}

void LandmarkComponent::Process(const message::Image& m) {
  const sensing::SonarScan* scan = ScanAt(m.header.stamp_ns);
  if (scan == nullptr) {
    ctx_.counters.Drop("robot/camera/image", "no sonar scan near the frame in time");
    return;
  }
  const std::optional<double> odometer_in = odometer_.At(m.header.stamp_ns, max_scan_age_ns_);
  if (!odometer_in) {
    ctx_.counters.Drop("robot/camera/image", "no odometry near the frame in time");
    return;
  }
  frames_++;
  const vision::ImageView view{static_cast<int>(m.width_px), static_cast<int>(m.height_px),
                               static_cast<int>(m.step_bytes), m.encoding, m.data.data(),
                               m.data.size()};
  const FrameOutcome out = pipeline_.Process(view, *scan);
  switch (out.kind) {
    case FrameOutcome::Kind::kBadFrame:
    case FrameOutcome::Kind::kNoRange:
      ctx_.counters.Drop("robot/camera/image", out.reason);
      return;
    case FrameOutcome::Kind::kNoDoor:
      no_door_++;
      return;
    case FrameOutcome::Kind::kObservation:
      break;
  }
  const sensing::LandmarkObservation& o = out.observation;
  message::LandmarkObservation msg;
  msg.header.stamp_ns = m.header.stamp_ns;
  msg.door_class = o.door_class;
  msg.width_in = o.width_in;
  msg.confidence = o.confidence;
  msg.left_jamb_px = o.footprints.lj_px;
  msg.right_jamb_px = o.footprints.rj_px;
  msg.range_in = o.range_in;
  msg.center_offset_in = out.center_offset_in;
  msg.look_angle_rad = o.look_angle_rad;
  msg.in_envelope = o.in_envelope;
  msg.odometry_distance_in = *odometer_in;
  msg.image_stamp_ns = m.header.stamp_ns;
  msg.mark = out.mark.mark;
  if (observations_.Publish(msg)) doors_++;
}

std::string LandmarkComponent::Summary() const {
  return fmt::format("{} frames processed, {} doors observed, {} frames without a door, {} "
                     "frames of the camera never seen",
                     frames_, doors_, no_door_, frames_missed_);
}

}  // namespace stickrep::landmark
