#include "landmark/landmark_pipeline.h"

#include <cmath>

namespace stickrep::landmark {

LandmarkPipeline::LandmarkPipeline(const sensing::RobotConfig& robot,
                                   vision::RibbonDetectorParams detector,
                                   sensing::LandmarkEstimatorConfig estimator)
    : robot_(robot), detector_(detector), estimator_(robot, std::move(estimator)) {}

FrameOutcome LandmarkPipeline::Process(const vision::ImageView& frame,
                                       const sensing::SonarScan& scan) const {
  FrameOutcome out;
  const int coaxial = robot_.camera.coaxial_sensor;
  if (coaxial >= static_cast<int>(scan.ranges_in.size()) || !scan.valid[coaxial]) {
    out.kind = FrameOutcome::Kind::kNoRange;
    out.reason = "no valid coaxial sonar range";
    return out;
  }
  const double range_in = scan.ranges_in[coaxial] + robot_.sonar_ring.head_radius_in;
  const vision::DetectResult detected = detector_.Detect(frame, range_in);
  if (!detected.ok()) {
    out.kind = FrameOutcome::Kind::kBadFrame;
    out.reason = std::string(vision::ToString(detected.status)) + ": " + detected.message;
    return out;
  }
  std::vector<sensing::JambCandidate> candidates;
  for (const vision::CandidatePair& p : detected.detection.pairs) {
    candidates.push_back({sensing::Footprints{p.left_px, p.right_px}, p.confidence});
  }
  out.candidates = static_cast<int>(candidates.size());
  const auto estimate = estimator_.Estimate(scan, candidates);
  if (!estimate.ok()) {
    out.kind = FrameOutcome::Kind::kNoDoor;
    out.reason = std::string(sensing::ToString(estimate.error())) + ": " + estimate.message();
    return out;
  }
  out.kind = FrameOutcome::Kind::kObservation;
  out.observation = *estimate;
  const double centre_px = 0.5 * (estimate->footprints.lj_px + estimate->footprints.rj_px);
  out.center_offset_in =
      estimate->range_in * std::tan(estimator_.camera().AngleOfColumn(centre_px));
  return out;
}

}  // namespace stickrep::landmark
