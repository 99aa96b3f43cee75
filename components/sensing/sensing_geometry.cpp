#include "sensing/sensing_geometry.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace stickrep::sensing {

namespace {

std::string Num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.6g", v);
  return buf;
}

Result<double> CheckRange(const char* name, double range_in) {
  if (!std::isfinite(range_in) || range_in <= 0.0) {
    return Result<double>::Fail(
        SensingError::kBadSonarRange,
        std::string(name) + " must be a finite range > 0 in, got " + Num(range_in));
  }
  return Result<double>::Ok(range_in);
}

Result<double> CheckWidth(double width_in) {
  if (!std::isfinite(width_in) || width_in <= 0.0) {
    return Result<double>::Fail(SensingError::kDegenerateGeometry,
                                "the geometry gives no positive finite width (" + Num(width_in) +
                                    " in): a ray misses the wall");
  }
  return Result<double>::Ok(width_in);
}

}  // namespace

const char* ToString(SensingError e) {
  switch (e) {
    case SensingError::kBadSonarRange:
      return "bad sonar range";
    case SensingError::kBadFootprint:
      return "bad footprint";
    case SensingError::kStareOutOfRange:
      return "stare out of range";
    case SensingError::kBadParameter:
      return "bad parameter";
    case SensingError::kDegenerateGeometry:
      return "degenerate geometry";
    case SensingError::kNoValidSonar:
      return "no valid sonar";
    case SensingError::kOutsideEveryClass:
      return "outside every class";
    case SensingError::kNoCandidate:
      return "no candidate";
    case SensingError::kOpenDoorUnresolved:
      return "open door unresolved";
  }
  return "unknown";
}

CameraModel CameraModel::FromConfig(const CameraConfig& c) {
  CameraModel m;
  m.fov_rad = DegToRad(c.fov_deg);
  m.width_px = c.image_width_px;
  m.pitch_over_focal = c.pixel_pitch_mm / c.focal_length_mm;
  m.k1 = c.radial_distortion_k1;
  return m;
}

Result<Footprints> CheckFootprints(const CameraModel& cam, const Footprints& fp) {
  if (!std::isfinite(fp.lj_px) || !std::isfinite(fp.rj_px)) {
    return Result<Footprints>::Fail(SensingError::kBadFootprint,
                                    "footprints must be finite columns, got LJ=" + Num(fp.lj_px) +
                                        " px, RJ=" + Num(fp.rj_px) + " px");
  }
  if (fp.lj_px < 0.0 || fp.rj_px > cam.width_px) {
    return Result<Footprints>::Fail(
        SensingError::kBadFootprint,
        "footprints must lie in the image [0, " + std::to_string(cam.width_px) +
            "] px, got LJ=" + Num(fp.lj_px) + " px, RJ=" + Num(fp.rj_px) + " px");
  }
  if (fp.lj_px >= fp.rj_px) {
    return Result<Footprints>::Fail(SensingError::kBadFootprint,
                                    "the left footprint must lie left of the right one, got LJ=" +
                                        Num(fp.lj_px) + " px >= RJ=" + Num(fp.rj_px) + " px");
  }
  return Result<Footprints>::Ok(fp);
}

Result<double> CheckTheta(double theta_rad) {
  if (!std::isfinite(theta_rad) || theta_rad <= -kPi / 3.0 || theta_rad >= kPi / 3.0) {
    return Result<double>::Fail(SensingError::kStareOutOfRange,
                                "theta must lie in (-60, 60) deg (Short Side Geometry, §5.3), "
                                "got " +
                                    Num(RadToDeg(theta_rad)) + " deg");
  }
  return Result<double>::Ok(theta_rad);
}

Result<double> TwoSideWidth(const CameraModel& cam, double rl_in, double rr_in,
                            const Footprints& fp) {
  if (auto r = CheckRange("RL", rl_in); !r) return r;
  if (auto r = CheckRange("RR", rr_in); !r) return r;
  if (auto f = CheckFootprints(cam, fp); !f) {
    return Result<double>::Fail(f.error(), f.message());
  }
  return CheckWidth(TwoSideWidthT<double>(cam, rl_in, rr_in, fp.lj_px, fp.rj_px));
}

Result<double> ShortSideWidth(const CameraModel& cam, double sdis_in, double theta_rad,
                              const Footprints& fp, ShortSideEdges edges) {
  if (auto r = CheckRange("sdis", sdis_in); !r) return r;
  if (auto t = CheckTheta(theta_rad); !t) return t;
  if (auto f = CheckFootprints(cam, fp); !f) {
    return Result<double>::Fail(f.error(), f.message());
  }
  return CheckWidth(ShortSideWidthT<double>(cam, sdis_in, theta_rad, fp.lj_px, fp.rj_px, edges));
}

Result<SceneTruth> MakeScene(const CameraModel& cam, const StareScene& scene) {
  using R = Result<SceneTruth>;
  if (!(scene.wall_distance_in > 0.0) || !std::isfinite(scene.wall_distance_in)) {
    return R::Fail(SensingError::kBadParameter, "wall distance must be > 0 in");
  }
  if (!(scene.door_width_in > 0.0) || !std::isfinite(scene.door_width_in) ||
      !std::isfinite(scene.door_offset_in)) {
    return R::Fail(SensingError::kBadParameter, "door width must be > 0 in");
  }
  const double theta = ThetaFromStare(scene.stare_rad);
  if (auto t = CheckTheta(theta); !t) return R::Fail(t.error(), t.message());
  const double d = scene.wall_distance_in;
  // Wall along x at y = d; a ray at angle a from the optical axis (positive right) meets it
  // at angle theta + a from the normal.
  const double half = cam.fov_rad / 2.0;
  SceneTruth t;
  t.theta_rad = theta;
  t.sdis_in = d;
  if (std::abs(theta) + half >= kPi / 2.0) {
    return R::Fail(SensingError::kDegenerateGeometry,
                   "a field-of-view edge is parallel to or leaves the wall");
  }
  t.rl_in = d / std::cos(theta - half);
  t.rr_in = d / std::cos(theta + half);
  t.sensor_l_in = d / std::cos(theta - kPi / 6.0);
  t.sensor_r_in = d / std::cos(theta + kPi / 6.0);
  const double xc = d * std::tan(theta) + scene.door_offset_in;
  const double a_l = std::atan((xc - scene.door_width_in / 2.0) / d) - theta;
  const double a_r = std::atan((xc + scene.door_width_in / 2.0) / d) - theta;
  if (a_l <= -half || a_r >= half) {
    return R::Fail(SensingError::kBadFootprint, "the door is not wholly inside the field of view");
  }
  t.footprints = {cam.ColumnOfAngle(a_l), cam.ColumnOfAngle(a_r)};
  return R::Ok(t);
}

}  // namespace stickrep::sensing
