#pragma once

#include <cmath>

#include "common/units.h"
#include "sensing/result.h"
#include "sensing/robot_config.h"

namespace stickrep::sensing {

// The pin-hole view of the camera that the sensing geometries need (constraint C7, §5.1):
// field of view, image width and the pixel pitch over focal length.
//
// Column convention: columns grow to the image's right; the angle of a column from the
// optical axis is atan(pitch * (col - mid) / f), positive to the right. §5.2 writes
// atan(2h(mid - LJ)/f); with h the pixel pitch that puts the image edge at 2x the stated
// FOV/2, so we read the factor 2 as belonging to a half-pitch h and use the physical
// pitch here (the edge column then sits at FOV/2, which CameraConfig::Validate checks).
struct CameraModel {
  double fov_rad = DegToRad(55.817);
  int width_px = 512;
  double pitch_over_focal = 0.012414 / 6.0;  // rad per pixel at the image centre
  // Radial distortion on the centre row, x_d = x_u (1 + k1 x_u^2) (CameraConfig).
  double k1 = 0.0;

  static CameraModel FromConfig(const CameraConfig& c);

  double mid_px() const { return width_px / 2.0; }
  // Angle of a column from the optical axis (positive to the right), the lens distortion
  // undone (Newton's method on the centre-row model; converges in a few steps for
  // |k1| x^2 << 1). T is double or an automatic-differentiation scalar.
  template <typename T>
  T AngleOfColumnT(const T& col_px) const;
  double AngleOfColumn(double col_px) const { return AngleOfColumnT(col_px); }
  double ColumnOfAngle(double angle_rad) const {
    const double xu = std::tan(angle_rad);
    return mid_px() + xu * (1.0 + k1 * xu * xu) / pitch_over_focal;
  }
};

namespace geometry_detail {

// atan for both double and Eigen::AutoDiffScalar (which provides atan2 but not atan).
template <typename T>
T Atan(const T& x) {
  using std::atan2;
  return atan2(x, T(1.0));
}

}  // namespace geometry_detail

template <typename T>
T CameraModel::AngleOfColumnT(const T& col_px) const {
  using geometry_detail::Atan;
  const T xd = (col_px - mid_px()) * pitch_over_focal;
  T xu = xd;
  for (int i = 0; i < 4 && k1 != 0.0; ++i) {
    xu = xu - (xu * (1.0 + k1 * xu * xu) - xd) / (1.0 + 3.0 * k1 * xu * xu);
  }
  return Atan(xu);
}

// The two jamb footprints of a candidate vertical edge ribbon, in image columns (§4.1.1).
struct Footprints {
  double lj_px = 0.0;
  double rj_px = 0.0;
};

// How the Short Side Geometry turns sdis and theta into RL and RR (§5.3).
enum class ShortSideEdges {
  // As printed: RL = sdis / sin(pi/3 + theta). The sides are the ranges along the rays of
  // the sensors two spacings (30°) off the optical axis, which approximate the 27.9° edges
  // of the field of view ("L -> RL" of Table 5.2).
  kPaperSensorRays,
  // RL = sdis / sin(pi/2 - FOV/2 + theta): the ranges along the field-of-view edges
  // themselves, removing that approximation.
  kFieldOfViewEdges,
};

// Stare delta (angle between optical axis and wall, 90° = square-on, §5.4) to the Short
// Side theta (angle between optical axis and wall normal). We take theta = delta - 90° so
// that at delta < 90° the left side RL is the oblique one, as in Tables 5.1 and 5.2.
inline double ThetaFromStare(double stare_rad) { return stare_rad - kPi / 2.0; }
inline double StareFromTheta(double theta_rad) { return theta_rad + kPi / 2.0; }

// Two Side Geometry (§5.2), unchecked; T is double or an automatic-differentiation scalar.
// The angle alpha at the left end of W_L is computed as atan2 instead of the printed
// arcsin(RR sin FOV / W_L): the two agree while alpha <= 90°, and atan2 stays right when
// the left edge meets the wall at an obtuse angle (theta > FOV/2 - 0).
template <typename T>
T TwoSideWidthT(const CameraModel& cam, const T& rl, const T& rr, const T& lj, const T& rj) {
  using geometry_detail::Atan;
  using std::atan2;
  using std::cos;
  using std::sin;
  using std::sqrt;
  const double fov = cam.fov_rad;
  const T wl = sqrt(rl * rl + rr * rr - 2.0 * rl * rr * cos(fov));  // Law of Cosines
  const T alpha = atan2(rr * sin(fov), rl - rr * cos(fov));
  const T phi_l = fov / 2.0 + cam.AngleOfColumnT(lj);
  const T phi_r = fov / 2.0 - cam.AngleOfColumnT(rj);
  const T d_l = rl * sin(phi_l) / sin(kPi - phi_l - alpha);  // Law of Sines
  const T d_r = rr * sin(phi_r) / sin(fov - phi_r + alpha);
  return wl - d_l - d_r;
}

// The two sides RL, RR of the Short Side Geometry (§5.3).
template <typename T>
void ShortSideSidesT(const CameraModel& cam, const T& sdis, const T& theta, ShortSideEdges edges,
                     T* rl, T* rr) {
  using std::sin;
  const double edge = edges == ShortSideEdges::kPaperSensorRays ? kPi / 6.0 : cam.fov_rad / 2.0;
  *rl = sdis / sin(kPi / 2.0 - edge + theta);
  *rr = sdis / sin(kPi / 2.0 - edge - theta);
}

// Short Side Geometry (§5.3), unchecked.
template <typename T>
T ShortSideWidthT(const CameraModel& cam, const T& sdis, const T& theta, const T& lj, const T& rj,
                  ShortSideEdges edges = ShortSideEdges::kPaperSensorRays) {
  T rl, rr;
  ShortSideSidesT(cam, sdis, theta, edges, &rl, &rr);
  return TwoSideWidthT(cam, rl, rr, lj, rj);
}

// Checked forms: reject NaN, non-positive ranges, footprints outside [0, width] or
// LJ >= RJ, theta outside (-pi/3, pi/3), and degenerate triangles.
Result<double> TwoSideWidth(const CameraModel& cam, double rl_in, double rr_in,
                            const Footprints& fp);
Result<double> ShortSideWidth(const CameraModel& cam, double sdis_in, double theta_rad,
                              const Footprints& fp,
                              ShortSideEdges edges = ShortSideEdges::kPaperSensorRays);

// Validity checks shared with the landmark estimator.
Result<Footprints> CheckFootprints(const CameraModel& cam, const Footprints& fp);
Result<double> CheckTheta(double theta_rad);

// A door seen from the robot: the ground truth the error analysis perturbs. The wall is at
// perpendicular distance wall_distance_in from the camera centre; the optical axis meets it
// at stare delta; the door centre sits door_offset_in along the wall (toward the image's
// right) from that point.
struct StareScene {
  double wall_distance_in = 72.0;
  double stare_rad = kPi / 2.0;
  double door_width_in = 36.0;
  double door_offset_in = 0.0;
};

// What a perfect sensor would report for a StareScene.
struct SceneTruth {
  double theta_rad = 0.0;
  double sdis_in = 0.0;      // perpendicular range to the wall
  double rl_in = 0.0;        // range along the left field-of-view edge
  double rr_in = 0.0;        // range along the right field-of-view edge
  double sensor_l_in = 0.0;  // range along the ray 30° left of the axis (ideal ray L)
  double sensor_r_in = 0.0;  // range along the ray 30° right of the axis (ideal ray R)
  Footprints footprints;     // jamb columns
};

// Fails when the door is not wholly inside the field of view or the stare is invalid.
Result<SceneTruth> MakeScene(const CameraModel& cam, const StareScene& scene);

}  // namespace stickrep::sensing
