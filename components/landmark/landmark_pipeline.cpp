#include "landmark/landmark_pipeline.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <utility>

#include "common/units.h"

namespace stickrep::landmark {

std::vector<sensing::JambCandidate> CandidatesAfterCasingRule(
    const vision::RibbonDetection& detection, const CasingRule& rule, int* casings) {
  const std::vector<vision::Footprint>& fp = detection.footprints;
  const std::vector<vision::CandidatePair>& pairs = detection.pairs;
  std::vector<double> confidence(pairs.size());
  std::vector<bool> withdrawn(pairs.size(), false);
  std::map<std::pair<int, int>, std::size_t> by_ends;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    confidence[i] = pairs[i].confidence;
    by_ends[{pairs[i].left_index, pairs[i].right_index}] = i;
  }
  int found = 0;
  if (rule.enabled) {
    // Outside in: widest pairs first, so a promoted confidence can pass further inward.
    std::vector<std::size_t> order(pairs.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return pairs[a].width_px > pairs[b].width_px;
    });
    auto find = [&](int l, int r) -> long {
      const auto it = by_ends.find({l, r});
      return it == by_ends.end() ? -1 : static_cast<long>(it->second);
    };
    const int n_fp = static_cast<int>(fp.size());
    for (std::size_t o : order) {
      if (withdrawn[o]) continue;
      const int a = pairs[o].left_index, d = pairs[o].right_index;
      // The bands are bounded by neighbouring footprints: nothing lies inside a casing.
      const int b = a + 1, c = d - 1;
      if (a < 0 || d >= n_fp || b >= c) continue;
      const int pa = fp[a].polarity, pb = fp[b].polarity, pc = fp[c].polarity, pd = fp[d].polarity;
      if (pa == 0 || pb == 0 || pa == pb || pc == pd || pa != -pd || pb != -pc) continue;
      if (std::min({fp[a].rows_hit, fp[b].rows_hit, fp[c].rows_hit, fp[d].rows_hit}) <
          rule.min_rows_hit) {
        continue;
      }
      const double left_band = fp[b].column_px - fp[a].column_px;
      const double right_band = fp[d].column_px - fp[c].column_px;
      const double opening = fp[c].column_px - fp[b].column_px;
      if (!(left_band > 0.0 && right_band > 0.0 && opening > 0.0)) continue;
      if (std::max(left_band, right_band) > rule.max_band_to_opening * opening) continue;
      if (std::max(left_band, right_band) > rule.max_band_ratio * std::min(left_band, right_band)) {
        continue;
      }
      const long inner = find(b, c);
      if (inner < 0 || withdrawn[inner]) continue;
      // Every pair from an outer casing edge to an edge within the frame (the outer pair,
      // the mixed pairs, the bands, and pairs to a double door's seam) is this landmark
      // seen wrongly; the opening carries the group's confidence.
      double best = confidence[inner];
      for (std::size_t k = 0; k < pairs.size(); ++k) {
        if (withdrawn[k] || static_cast<long>(k) == inner) continue;
        const int l = pairs[k].left_index, r = pairs[k].right_index;
        if ((l == a && r <= d) || (r == d && l >= a)) {
          best = std::max(best, confidence[k]);
          withdrawn[k] = true;
        }
      }
      confidence[inner] = best;
      ++found;
    }
  }
  if (casings) *casings = found;
  std::vector<sensing::JambCandidate> out;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    if (withdrawn[i]) continue;
    out.push_back({sensing::Footprints{pairs[i].left_px, pairs[i].right_px}, confidence[i]});
  }
  return out;
}

vision::PairWidthLimits LegalPairWidths(const sensing::CameraModel& camera, double sdis_in,
                                        double theta_rad, double min_width_in,
                                        double max_width_in, const WidthGate& gate) {
  constexpr int kPlaces = 24;
  const double half_fov = camera.fov_rad / 2.0;
  const double dtheta = gate.stare_tolerance_deg * kPi / 180.0;
  vision::PairWidthLimits out{1e9, 0.0};
  for (double d : {sdis_in * (1.0 - gate.range_tolerance), sdis_in * (1.0 + gate.range_tolerance)}) {
    for (double th : {theta_rad - dtheta, theta_rad, theta_rad + dtheta}) {
      // The wall along x at distance d; a ray at angle a from the optical axis meets it at
      // x = d tan(th + a). Doors of either width anywhere from the left edge of the view to
      // the right one.
      if (std::abs(th) + half_fov >= 0.5 * kPi - 1e-3) continue;
      const double x_lo = d * std::tan(th - half_fov), x_hi = d * std::tan(th + half_fov);
      for (double width : {min_width_in, max_width_in}) {
        for (int k = 0; k <= kPlaces; ++k) {
          const double x0 = x_lo + (x_hi - x_lo - width) * k / kPlaces;
          if (x0 < x_lo || x0 + width > x_hi) continue;
          const double px = camera.ColumnOfAngle(std::atan((x0 + width) / d) - th) -
                            camera.ColumnOfAngle(std::atan(x0 / d) - th);
          if (width == min_width_in) out.min_px = std::min(out.min_px, px);
          if (width == max_width_in) out.max_px = std::max(out.max_px, px);
        }
      }
    }
  }
  if (out.max_px <= 0.0) return vision::PairWidthLimits{};  // nothing fits: no gate
  // Sub-pixel jamb error (§5.5: up to 5 px each) on both sides.
  out.min_px = std::max(0.0, out.min_px - 2.0);
  out.max_px += 2.0;
  return out;
}

LandmarkPipeline::LandmarkPipeline(const sensing::RobotConfig& robot,
                                   vision::RibbonDetectorParams detector,
                                   sensing::LandmarkEstimatorConfig estimator, CasingRule casing,
                                   WidthGate gate)
    : robot_(robot),
      detector_(detector),
      estimator_(robot, std::move(estimator)),
      casing_(casing),
      gate_(gate) {
  marks_.camera_height_in = detector.camera_height_in;
  marks_.focal_px = detector.focal_px;
  min_class_in_ = 1e9;
  for (const sensing::ClassBoundary& b : sensing::DefaultBoundaries()) {
    min_class_in_ = std::min(min_class_in_, b.low_in);
    max_class_in_ = std::max(max_class_in_, b.high_in);
  }
}

vision::PairWidthLimits LandmarkPipeline::GateLimits(const sensing::SonarScan& scan) const {
  if (!gate_.enabled) return {};
  const sensing::SonarRingModel& ring = estimator_.ring();
  int best = -1;
  for (int k = 0; k < ring.count && k < static_cast<int>(scan.ranges_in.size()) &&
                  k < static_cast<int>(scan.valid.size());
       ++k) {
    if (!scan.valid[k] || !std::isfinite(scan.ranges_in[k]) ||
        std::abs(ring.BearingOf(k)) >= kPi / 3.0) {
      continue;
    }
    if (best < 0 || scan.ranges_in[k] < scan.ranges_in[best]) best = k;
  }
  if (best < 0) return {};
  // As the Short Side reads them (§5.3): the nearest sensor faces the wall.
  const double theta = -ring.BearingOf(best);
  const double sdis = scan.ranges_in[best] + ring.head_radius_in -
                      robot_.camera.offset_forward_in * std::cos(theta);
  if (!(sdis > 0.0)) return {};
  return LegalPairWidths(estimator_.camera(), sdis, theta, min_class_in_,
                         max_class_in_ + 2.0 * gate_.casing_allowance_in, gate_);
}

FrameOutcome LandmarkPipeline::Process(const vision::ImageView& frame,
                                       const sensing::SonarScan& scan) const {
  return Process(frame, scan, nullptr);
}

FrameOutcome LandmarkPipeline::Process(const vision::ImageView& frame,
                                       const sensing::SonarScan& scan,
                                       vision::RibbonDetection* detection) const {
  FrameOutcome out;
  const int coaxial = robot_.camera.coaxial_sensor;
  if (coaxial < 0 || coaxial >= static_cast<int>(scan.ranges_in.size()) ||
      coaxial >= static_cast<int>(scan.valid.size()) || !scan.valid[coaxial] ||
      !std::isfinite(scan.ranges_in[coaxial])) {
    out.kind = FrameOutcome::Kind::kNoRange;
    out.reason = "no valid coaxial sonar range";
    return out;
  }
  const double range_in = scan.ranges_in[coaxial] + robot_.sonar_ring.head_radius_in;
  out.width_limits = GateLimits(scan);
  const vision::DetectResult detected = detector_.Detect(frame, range_in, out.width_limits);
  if (!detected.ok()) {
    out.kind = FrameOutcome::Kind::kBadFrame;
    out.reason = std::string(vision::ToString(detected.status)) + ": " + detected.message;
    return out;
  }
  out.candidates = static_cast<int>(detected.detection.pairs.size());
  out.pairs_before_cap = detected.detection.pairs_before_cap;
  if (detection) *detection = detected.detection;
  out.ranked = CandidatesAfterCasingRule(detected.detection, casing_, &out.casings);
  const std::vector<sensing::JambCandidate>& candidates = out.ranked;
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
  out.mark = vision::ReadDoorMark(frame, estimate->footprints.lj_px, estimate->footprints.rj_px,
                                  estimate->range_in, marks_);
  return out;
}

}  // namespace stickrep::landmark
