#pragma once

#include <array>
#include <random>
#include <string>
#include <vector>

#include "sensing/result.h"
#include "sensing/sensing_geometry.h"
#include "sensing/sonar_model.h"

namespace stickrep::sensing {

// The two fused sensing geometries of Chapter 5.
enum class Geometry { kTwoSide, kShortSide };
const char* ToString(Geometry g);

// Range errors of Table 5.2 (percent of the range), at one stare. "approx" is the
// difference between the ideal sensor ray (30° off the axis) and the field-of-view edge
// (L -> RL, R -> RR); "returned" is the worst-case error of the returned range against the
// ideal ray (d_L -> L, d_R -> R: cone geometry plus the surface errors of §4.3).
struct CompositeRangeError {
  double approx_l_pct = 0.0;
  double approx_r_pct = 0.0;
  double returned_l_pct = 0.0;
  double returned_r_pct = 0.0;
};

// Table 5.2 as printed (stares 90°, 70°, 50°); linear in between, mirrored (L <-> R) for
// stares above 90°; fails outside [50°, 130°] where the text gives no figures.
Result<CompositeRangeError> Table52(double stare_rad);
// The approximation columns computed from the geometry: |L - RL| / L and |R - RR| / R.
CompositeRangeError ApproximationFromGeometry(const CameraModel& cam, double stare_rad);

// The worst-case input errors of §5.4 and the surface the sonar ranges.
struct ErrorBounds {
  double delta_theta_rad = 7.5 * kPi / 180.0;  // §5.3: half the 15° sensor spacing
  double delta_footprint_px = 5.0;             // §5.4.3: "five pixels"
  // Surface behind the short-side reading (Tables 4.2/4.3): concrete, "a common domain
  // feature surface", the worse of the two hard surfaces near normal incidence.
  Surface surface = Surface::kConcrete;
  UltrasoundExperiment experiment = UltrasoundExperiment::kWorseOfBoth;
};

// Percent error bound of the short-side range when its sensor is `incidence_rad` off the
// normal: the mean of Table 4.2/4.3 (their sigma is at most 0.09 % on concrete and wood).
Result<double> ShortRangeErrorPct(const ErrorBounds& b, double incidence_rad);

// One input of the first-order model: the partial derivative of the width (in per unit of
// the input, radians for theta), the worst-case input error, and their product.
struct LinearTerm {
  std::string input;
  double partial = 0.0;
  double delta = 0.0;
  double contribution_in = 0.0;  // partial * delta (signed)
};

// The linear first-order error model of §5.4.3 (Figure 5.3) at one stare.
struct LinearEstimate {
  Geometry geometry = Geometry::kShortSide;
  double stare_rad = 0.0;
  double width_in = 0.0;  // the geometry's width from error-free inputs
  std::array<LinearTerm, 4> terms;
  double worst_case_in = 0.0;   // sum of |partial * delta|: every sign at its worst
  double dot_product_in = 0.0;  // |gradient . delta| with every delta positive
};

// Gradients by forward-mode automatic differentiation (Eigen AutoDiffScalar).
// Two Side: d/d(RL, RR, LJ, RJ); Short Side: d/d(sdis, theta, LJ, RJ).
std::array<double, 4> TwoSideGradient(const CameraModel& cam, double rl_in, double rr_in,
                                      const Footprints& fp);
std::array<double, 4> ShortSideGradient(const CameraModel& cam, double sdis_in, double theta_rad,
                                        const Footprints& fp, ShortSideEdges edges);

Result<LinearEstimate> LinearFirstOrder(const CameraModel& cam, const StareScene& scene,
                                        Geometry geometry, const ErrorBounds& bounds,
                                        ShortSideEdges edges = ShortSideEdges::kPaperSensorRays);

// Table 5.5: the largest delta theta (rad) whose worst-case Short Side error stays within
// `tolerance_in`; 0 if even a perfect theta exceeds it, `max_rad` if it never does.
Result<double> ShortSideThetaTolerance(const CameraModel& cam, const StareScene& scene,
                                       ErrorBounds bounds, double tolerance_in,
                                       double max_rad = kPi / 3.0);

// The Monte Carlo experiment of §5.5.
//
// Every worst-case bound of §5.4 enters as a uniform draw within it (the text gives bounds,
// not distributions, and itself draws delta theta uniformly): theta error in +-7.5°, each
// footprint in +-5 px; Two Side ranges: the true range along the 30° sensor ray (so the
// L -> RL approximation enters through the geometry) times (1 + u), u uniform within the
// d -> L / d -> R percentages of Table 5.2; Short Side range: the true perpendicular range
// times (1 + u), u uniform within the Table 4.2/4.3 error of the surface at the trial's
// incidence |delta theta|.
struct MonteCarloConfig {
  int trials = 10000;
  ErrorBounds bounds;
  ShortSideEdges edges = ShortSideEdges::kPaperSensorRays;
  double tolerance_in = 2.0;  // Table 5.6: "within 2 inches"
};

struct MonteCarloResult {
  Geometry geometry = Geometry::kShortSide;
  double stare_rad = 0.0;
  int trials = 0;
  int rejected = 0;               // trials the geometry refused (none expected in the envelope)
  std::vector<double> errors_in;  // measured - true width, one per accepted trial
  double mean_error_in = 0.0;
  double stddev_in = 0.0;
  double p_within_tolerance = 0.0;  // share of all trials with |error| <= tolerance
};

Result<MonteCarloResult> RunMonteCarlo(const CameraModel& cam, const StareScene& scene,
                                       Geometry geometry, const MonteCarloConfig& config,
                                       std::mt19937_64& rng);

}  // namespace stickrep::sensing
