#include "sensing/landmark_estimator.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

namespace stickrep::sensing {

struct LandmarkEstimator::Ranges {
  double sdis_in = 0.0;
  double theta_rad = 0.0;
};

namespace {

std::string Num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.4g", v);
  return buf;
}

// Least-squares wall (perpendicular distance from the ring centre, bearing of its normal)
// through flank readings, with the returned-range model of §5.4.1: Gauss-Newton.
bool FitWall(const SonarRingModel& ring, const std::vector<double>& bearings,
             const std::vector<double>& ranges, double* distance_in, double* normal_rad) {
  double d = *distance_in, nu = *normal_rad;
  auto residuals = [&](double dd, double nn, std::vector<double>* r) {
    r->clear();
    for (std::size_t i = 0; i < bearings.size(); ++i) {
      const auto pred = ReturnedRange(ring, dd, bearings[i] - nn);
      if (!pred) return false;
      r->push_back(*pred - ranges[i]);
    }
    return true;
  };
  std::vector<double> r0, rd, rn;
  for (int it = 0; it < 30; ++it) {
    if (!residuals(d, nu, &r0)) return false;
    const double hd = 1e-3, hn = 1e-5;
    if (!residuals(d + hd, nu, &rd) || !residuals(d, nu + hn, &rn)) return false;
    double a11 = 0, a12 = 0, a22 = 0, b1 = 0, b2 = 0;
    for (std::size_t i = 0; i < r0.size(); ++i) {
      const double jd = (rd[i] - r0[i]) / hd, jn = (rn[i] - r0[i]) / hn;
      a11 += jd * jd;
      a12 += jd * jn;
      a22 += jn * jn;
      b1 += jd * r0[i];
      b2 += jn * r0[i];
    }
    const double det = a11 * a22 - a12 * a12;
    if (std::abs(det) < 1e-12) return false;
    const double step_d = (a22 * b1 - a12 * b2) / det;
    const double step_n = (a11 * b2 - a12 * b1) / det;
    d -= step_d;
    nu -= std::clamp(step_n, -0.2, 0.2);
    if (std::abs(step_d) < 1e-6 && std::abs(step_n) < 1e-9) break;
  }
  if (!std::isfinite(d) || d <= 0.0) return false;
  *distance_in = d;
  *normal_rad = nu;
  return true;
}

// A scan with one range and one validity flag per sensor, each valid range inside the
// ring's working range.
Result<bool> CheckScan(const SonarRingModel& ring, const SonarScan& scan) {
  const std::size_t n = static_cast<std::size_t>(ring.count);
  if (scan.ranges_in.size() != n || scan.valid.size() != n) {
    return Result<bool>::Fail(
        SensingError::kBadSonarRange,
        "a scan needs " + std::to_string(n) + " ranges and validity flags, got " +
            std::to_string(scan.ranges_in.size()) + " and " + std::to_string(scan.valid.size()));
  }
  for (std::size_t k = 0; k < n; ++k) {
    if (scan.valid[k] && !ring.InRange(scan.ranges_in[k])) {
      return Result<bool>::Fail(
          SensingError::kBadSonarRange,
          "sensor " + std::to_string(k) + " is flagged valid but reads " + Num(scan.ranges_in[k]) +
              " in (valid: " + Num(ring.min_range_in) + ".." + Num(ring.max_range_in) + " in)");
    }
  }
  return Result<bool>::Ok(true);
}

// Every candidate well formed, not only the ones that will be tried.
Result<bool> CheckCandidates(const CameraModel& camera,
                             const std::vector<JambCandidate>& candidates) {
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const auto fp = CheckFootprints(camera, candidates[i].footprints);
    if (!fp) {
      return Result<bool>::Fail(fp.error(), "candidate " + std::to_string(i) + ": " + fp.message());
    }
    if (!std::isfinite(candidates[i].confidence)) {
      return Result<bool>::Fail(SensingError::kBadFootprint,
                                "candidate " + std::to_string(i) + ": confidence is not finite");
    }
  }
  return Result<bool>::Ok(true);
}

// Indices of the candidates at or above the threshold, in decreasing confidence (ties in
// the caller's order).
std::vector<std::size_t> ByConfidence(const std::vector<JambCandidate>& candidates,
                                      double min_confidence) {
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (candidates[i].confidence >= min_confidence) order.push_back(i);
  }
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return candidates[a].confidence > candidates[b].confidence;
  });
  return order;
}

}  // namespace

LandmarkEstimator::LandmarkEstimator(const RobotConfig& robot, LandmarkEstimatorConfig config)
    : camera_(CameraModel::FromConfig(robot.camera)),
      ring_(SonarRingModel::FromConfig(robot)),
      camera_offset_in_(robot.camera.offset_forward_in),
      config_(std::move(config)) {}

Result<LandmarkEstimator::Ranges> LandmarkEstimator::ShortSideRanges(
    const std::vector<double>& ranges, const std::vector<bool>& valid) const {
  // §5.3: the shortest range of the sensors that can face the wall within the valid theta
  // interval is the sensor nearest the normal.
  int best = -1;
  for (int k = 0; k < ring_.count; ++k) {
    if (!valid[k] || std::abs(ring_.BearingOf(k)) >= kPi / 3.0) continue;
    if (best < 0 || ranges[k] < ranges[best]) best = k;
  }
  if (best < 0) {
    return Result<Ranges>::Fail(SensingError::kNoValidSonar,
                                "no valid sonar reading within 60 deg of the optical axis");
  }
  Ranges out;
  out.theta_rad = -ring_.BearingOf(best);
  // The sensor faces the wall within half a spacing: its range plus the head radius is the
  // centre's perpendicular distance; the camera sits offset_forward_in ahead on the axis.
  out.sdis_in = ranges[best] + ring_.head_radius_in - camera_offset_in_ * std::cos(out.theta_rad);
  return Result<Ranges>::Ok(out);
}

Result<bool> LandmarkEstimator::FillOpenDoor(const Footprints& fp, std::vector<double>* ranges,
                                             std::vector<bool>* valid) const {
  const double a_l = camera_.AngleOfColumn(fp.lj_px);
  const double a_r = camera_.AngleOfColumn(fp.rj_px);
  const double flank_limit = camera_.fov_rad / 2.0 + ring_.spacing_rad;
  std::vector<int> inside, flank;
  for (int k = 0; k < ring_.count; ++k) {
    const double b = ring_.BearingOf(k);
    if (b >= a_l && b <= a_r) {
      inside.push_back(k);
    } else if (std::abs(b) <= flank_limit && (*valid)[k]) {
      flank.push_back(k);
    }
  }
  if (inside.empty()) return Result<bool>::Ok(false);
  // Nearest valid flank reading on each side of the span.
  auto nearest = [&](bool left) -> int {
    int best = -1;
    for (int k : flank) {
      const double b = ring_.BearingOf(k);
      if (left ? b >= a_l : b <= a_r) continue;
      if (best < 0 || std::abs(b) < std::abs(ring_.BearingOf(best))) best = k;
    }
    return best;
  };
  const int left = nearest(true), right = nearest(false);
  bool edge = false;
  for (int k : inside) {
    if (!(*valid)[k]) continue;
    const double r = (*ranges)[k];
    const bool off_l = left < 0 || std::abs(r - (*ranges)[left]) > config_.open_door_depth_edge_in;
    const bool off_r =
        right < 0 || std::abs(r - (*ranges)[right]) > config_.open_door_depth_edge_in;
    if (off_l && off_r && (left >= 0 || right >= 0)) edge = true;
  }
  if (!edge) return Result<bool>::Ok(false);
  return FillFromFlankWall(flank, inside, ranges, valid);
}

Result<bool> LandmarkEstimator::FillFromFlankWall(const std::vector<int>& flank,
                                                  const std::vector<int>& inside,
                                                  std::vector<double>* ranges,
                                                  std::vector<bool>* valid) const {
  if (flank.size() < 2) {
    return Result<bool>::Fail(SensingError::kOpenDoorUnresolved,
                              "depth edge inside the door but fewer than two flank readings");
  }
  std::vector<double> bearings, flank_ranges;
  int nearest_k = flank.front();
  for (int k : flank) {
    bearings.push_back(ring_.BearingOf(k));
    flank_ranges.push_back((*ranges)[k]);
    if ((*ranges)[k] < (*ranges)[nearest_k]) nearest_k = k;
  }
  double distance = (*ranges)[nearest_k] + ring_.head_radius_in;
  double normal = ring_.BearingOf(nearest_k);
  if (!FitWall(ring_, bearings, flank_ranges, &distance, &normal)) {
    return Result<bool>::Fail(SensingError::kOpenDoorUnresolved,
                              "the flank readings do not fit a wall line");
  }
  for (int k : inside) {
    const auto pred = ReturnedRange(ring_, distance, ring_.BearingOf(k) - normal);
    if (!pred) {
      return Result<bool>::Fail(SensingError::kOpenDoorUnresolved,
                                "the fitted wall gives no echo inside the door");
    }
    (*ranges)[k] = *pred;
    (*valid)[k] = true;
  }
  return Result<bool>::Ok(true);
}

Result<LandmarkObservation> LandmarkEstimator::Estimate(
    const SonarScan& scan, const std::vector<JambCandidate>& candidates,
    std::optional<double> lateral_offset_in) const {
  using R = Result<LandmarkObservation>;
  if (const auto ok = CheckScan(ring_, scan); !ok) return R::Fail(ok.error(), ok.message());
  if (const auto ok = CheckCandidates(camera_, candidates); !ok) {
    return R::Fail(ok.error(), ok.message());
  }
  if (lateral_offset_in && !std::isfinite(*lateral_offset_in)) {
    return R::Fail(SensingError::kBadParameter, "lateral offset is not finite");
  }

  const std::vector<std::size_t> order = ByConfidence(candidates, config_.min_confidence);
  if (order.empty()) {
    return R::Fail(SensingError::kNoCandidate, "no candidate at or above the confidence threshold");
  }

  std::string tried;
  std::optional<R> last_failure;
  for (std::size_t idx : order) {
    const JambCandidate& c = candidates[idx];
    std::vector<double> ranges = scan.ranges_in;
    std::vector<bool> valid = scan.valid;
    const auto open = FillOpenDoor(c.footprints, &ranges, &valid);
    if (!open) {
      last_failure = R::Fail(open.error(), open.message());
      continue;
    }
    const auto rs = ShortSideRanges(ranges, valid);
    if (!rs) return R::Fail(rs.error(), rs.message());
    Result<double> width = Result<double>::Fail(SensingError::kBadParameter, "");
    if (config_.geometry == Geometry::kShortSide) {
      width = ShortSideWidth(camera_, rs->sdis_in, rs->theta_rad, c.footprints,
                             config_.short_side_edges);
    } else {
      const int kl = ((ring_.coaxial_sensor - 2) % ring_.count + ring_.count) % ring_.count;
      const int kr = (ring_.coaxial_sensor + 2) % ring_.count;
      if (!valid[kl] || !valid[kr]) {
        return R::Fail(SensingError::kNoValidSonar,
                       "the Two Side Geometry needs the sensors 30 deg either side of the axis");
      }
      const double shift = ring_.head_radius_in - camera_offset_in_ * std::cos(kPi / 6.0);
      width = TwoSideWidth(camera_, ranges[kl] + shift, ranges[kr] + shift, c.footprints);
    }
    if (!width) {
      last_failure = R::Fail(width.error(), width.message());
      continue;
    }
    const auto cls = ClassifyWidth(config_.classes, *width);
    if (!cls) {
      tried += (tried.empty() ? "" : ", ") + Num(*width);
      continue;
    }
    return R::Ok(Observation(c, idx, *cls, *width, *rs, *open, lateral_offset_in));
  }
  if (!tried.empty()) {
    return R::Fail(SensingError::kOutsideEveryClass,
                   "no candidate width falls in a door class (widths " + tried + " in)");
  }
  return *last_failure;
}

LandmarkObservation LandmarkEstimator::Observation(const JambCandidate& c, std::size_t idx,
                                                   DoorClass door_class, double width_in,
                                                   const Ranges& rs, bool open_door,
                                                   std::optional<double> lateral_offset_in) const {
  LandmarkObservation obs;
  obs.door_class = door_class;
  obs.width_in = width_in;
  obs.confidence = c.confidence;
  obs.footprints = c.footprints;
  obs.candidate_index = static_cast<int>(idx);
  obs.range_in = rs.sdis_in;
  obs.theta_rad = rs.theta_rad;
  obs.look_angle_rad = StareFromTheta(rs.theta_rad);
  obs.open_door = open_door;
  obs.in_envelope =
      std::abs(rs.theta_rad) <= config_.envelope_axis_angle_rad &&
      (!lateral_offset_in || std::abs(*lateral_offset_in) <= config_.envelope_lateral_in);
  return obs;
}

}  // namespace stickrep::sensing
