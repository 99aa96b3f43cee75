#include "sensing/error_analysis.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <unsupported/Eigen/AutoDiff>

namespace stickrep::sensing {

namespace {

using Ad = Eigen::AutoDiffScalar<Eigen::Matrix<double, 4, 1>>;

Ad Seed(double value, int index) { return Ad(value, 4, index); }

std::array<double, 4> Gradient(const Ad& w) {
  return {w.derivatives()[0], w.derivatives()[1], w.derivatives()[2], w.derivatives()[3]};
}

// Table 5.2 rows: stare (deg), L -> RL, R -> RR, d_L -> L, d_R -> R (percent).
struct Table52Row {
  double stare_deg;
  CompositeRangeError e;
};
constexpr Table52Row kTable52[] = {
    {50.0, {9.1, 0.72, 21.0, 1.5}},
    {70.0, {4.1, 0.57, 15.0, 2.1}},
    {90.0, {2.0, 2.0, 4.3, 5.1}},
};

CompositeRangeError Lerp(const CompositeRangeError& a, const CompositeRangeError& b, double t) {
  return {a.approx_l_pct + t * (b.approx_l_pct - a.approx_l_pct),
          a.approx_r_pct + t * (b.approx_r_pct - a.approx_r_pct),
          a.returned_l_pct + t * (b.returned_l_pct - a.returned_l_pct),
          a.returned_r_pct + t * (b.returned_r_pct - a.returned_r_pct)};
}

double Uniform(std::mt19937_64& rng, double half_width) {
  // 53 random bits to [0, 1), then to [-half_width, half_width).
  const double u = static_cast<double>(rng() >> 11) * 0x1.0p-53;
  return (2.0 * u - 1.0) * half_width;
}

}  // namespace

const char* ToString(Geometry g) { return g == Geometry::kTwoSide ? "Two Side" : "Short Side"; }

Result<CompositeRangeError> Table52(double stare_rad) {
  double s = RadToDeg(stare_rad);
  const bool mirrored = s > 90.0;
  if (mirrored) s = 180.0 - s;
  if (!(s >= 50.0 - 1e-9 && s <= 90.0 + 1e-9)) {
    return Result<CompositeRangeError>::Fail(
        SensingError::kStareOutOfRange,
        "Table 5.2 covers stares 50..130 deg only, got " + std::to_string(RadToDeg(stare_rad)));
  }
  s = std::clamp(s, 50.0, 90.0);
  const int i = s < 70.0 ? 0 : 1;
  CompositeRangeError e =
      Lerp(kTable52[i].e, kTable52[i + 1].e, (s - kTable52[i].stare_deg) / 20.0);
  if (mirrored) {
    std::swap(e.approx_l_pct, e.approx_r_pct);
    std::swap(e.returned_l_pct, e.returned_r_pct);
  }
  return Result<CompositeRangeError>::Ok(e);
}

CompositeRangeError ApproximationFromGeometry(const CameraModel& cam, double stare_rad) {
  const double theta = ThetaFromStare(stare_rad);
  const double half = cam.fov_rad / 2.0;
  // Ranges per unit perpendicular distance: ideal sensor rays at 30°, field-of-view edges.
  const double l = 1.0 / std::cos(theta - kPi / 6.0);
  const double r = 1.0 / std::cos(theta + kPi / 6.0);
  const double rl = 1.0 / std::cos(theta - half);
  const double rr = 1.0 / std::cos(theta + half);
  CompositeRangeError e;
  e.approx_l_pct = 100.0 * std::abs(l - rl) / l;
  e.approx_r_pct = 100.0 * std::abs(r - rr) / r;
  return e;
}

Result<double> ShortRangeErrorPct(const ErrorBounds& b, double incidence_rad) {
  const auto e = SurfaceRangeError(b.surface, incidence_rad, b.experiment);
  if (!e) {
    return Result<double>::Fail(SensingError::kBadParameter,
                                std::string("gross ranging error on ") + ToString(b.surface) +
                                    " at this incidence (Tables 4.2/4.3 '++')");
  }
  return Result<double>::Ok(e->mean_pct);
}

std::array<double, 4> TwoSideGradient(const CameraModel& cam, double rl_in, double rr_in,
                                      const Footprints& fp) {
  return Gradient(
      TwoSideWidthT<Ad>(cam, Seed(rl_in, 0), Seed(rr_in, 1), Seed(fp.lj_px, 2), Seed(fp.rj_px, 3)));
}

std::array<double, 4> ShortSideGradient(const CameraModel& cam, double sdis_in, double theta_rad,
                                        const Footprints& fp, ShortSideEdges edges) {
  return Gradient(ShortSideWidthT<Ad>(cam, Seed(sdis_in, 0), Seed(theta_rad, 1), Seed(fp.lj_px, 2),
                                      Seed(fp.rj_px, 3), edges));
}

Result<LinearEstimate> LinearFirstOrder(const CameraModel& cam, const StareScene& scene,
                                        Geometry geometry, const ErrorBounds& bounds,
                                        ShortSideEdges edges) {
  using R = Result<LinearEstimate>;
  const auto truth = MakeScene(cam, scene);
  if (!truth) return R::Fail(truth.error(), truth.message());
  const SceneTruth& t = *truth;
  LinearEstimate est;
  est.geometry = geometry;
  est.stare_rad = scene.stare_rad;
  std::array<double, 4> grad;
  std::array<double, 4> delta;
  std::array<const char*, 4> names;
  if (geometry == Geometry::kTwoSide) {
    const auto table = Table52(scene.stare_rad);
    if (!table) return R::Fail(table.error(), table.message());
    // The Two Side sides are the returned ranges of the sensors 30° off the axis: their
    // error against the field-of-view edge is the approximation plus the returned error.
    const double d_rl =
        std::abs(t.sensor_l_in - t.rl_in) + table->returned_l_pct / 100.0 * t.sensor_l_in;
    const double d_rr =
        std::abs(t.sensor_r_in - t.rr_in) + table->returned_r_pct / 100.0 * t.sensor_r_in;
    est.width_in =
        TwoSideWidthT<double>(cam, t.rl_in, t.rr_in, t.footprints.lj_px, t.footprints.rj_px);
    grad = TwoSideGradient(cam, t.rl_in, t.rr_in, t.footprints);
    delta = {d_rl, d_rr, bounds.delta_footprint_px, bounds.delta_footprint_px};
    names = {"RL", "RR", "LJ", "RJ"};
  } else {
    const auto pct = ShortRangeErrorPct(bounds, bounds.delta_theta_rad);
    if (!pct) return R::Fail(pct.error(), pct.message());
    est.width_in = ShortSideWidthT<double>(cam, t.sdis_in, t.theta_rad, t.footprints.lj_px,
                                           t.footprints.rj_px, edges);
    grad = ShortSideGradient(cam, t.sdis_in, t.theta_rad, t.footprints, edges);
    delta = {*pct / 100.0 * t.sdis_in, bounds.delta_theta_rad, bounds.delta_footprint_px,
             bounds.delta_footprint_px};
    names = {"sdis", "theta", "LJ", "RJ"};
  }
  double dot = 0.0;
  for (int i = 0; i < 4; ++i) {
    est.terms[i] = {names[i], grad[i], delta[i], grad[i] * delta[i]};
    est.worst_case_in += std::abs(grad[i] * delta[i]);
    dot += grad[i] * delta[i];
  }
  est.dot_product_in = std::abs(dot);
  return R::Ok(est);
}

Result<double> ShortSideThetaTolerance(const CameraModel& cam, const StareScene& scene,
                                       ErrorBounds bounds, double tolerance_in, double max_rad) {
  auto worst = [&](double dtheta) -> Result<double> {
    bounds.delta_theta_rad = dtheta;
    const auto e = LinearFirstOrder(cam, scene, Geometry::kShortSide, bounds);
    if (!e) return Result<double>::Fail(e.error(), e.message());
    return Result<double>::Ok(e->worst_case_in);
  };
  // The sdis bound grows with the incidence and turns gross past 45°: cap the search there.
  max_rad = std::min(max_rad, kPi / 4.0);
  const auto at0 = worst(0.0);
  if (!at0) return at0;
  if (*at0 > tolerance_in) return Result<double>::Ok(0.0);
  const auto atmax = worst(max_rad);
  if (atmax && *atmax <= tolerance_in) return Result<double>::Ok(max_rad);
  double lo = 0.0, hi = max_rad;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    const auto w = worst(mid);
    if (w && *w <= tolerance_in) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return Result<double>::Ok(lo);
}

Result<MonteCarloResult> RunMonteCarlo(const CameraModel& cam, const StareScene& scene,
                                       Geometry geometry, const MonteCarloConfig& config,
                                       std::mt19937_64& rng) {
  using R = Result<MonteCarloResult>;
  if (config.trials <= 0) return R::Fail(SensingError::kBadParameter, "trials must be > 0");
  const auto truth = MakeScene(cam, scene);
  if (!truth) return R::Fail(truth.error(), truth.message());
  const SceneTruth& t = *truth;
  const ErrorBounds& b = config.bounds;
  CompositeRangeError table;
  if (geometry == Geometry::kTwoSide) {
    const auto row = Table52(scene.stare_rad);
    if (!row) return R::Fail(row.error(), row.message());
    table = *row;
  }
  MonteCarloResult out;
  out.geometry = geometry;
  out.stare_rad = scene.stare_rad;
  out.trials = config.trials;
  out.errors_in.reserve(config.trials);
  const double truth_width = scene.door_width_in;
  int within = 0;
  for (int i = 0; i < config.trials; ++i) {
    const double lj = t.footprints.lj_px + Uniform(rng, b.delta_footprint_px);
    const double rj = t.footprints.rj_px + Uniform(rng, b.delta_footprint_px);
    double width;
    if (geometry == Geometry::kTwoSide) {
      const double rl = t.sensor_l_in * (1.0 + Uniform(rng, table.returned_l_pct / 100.0));
      const double rr = t.sensor_r_in * (1.0 + Uniform(rng, table.returned_r_pct / 100.0));
      width = TwoSideWidthT<double>(cam, rl, rr, lj, rj);
    } else {
      const double dtheta = Uniform(rng, b.delta_theta_rad);
      const auto e = SurfaceRangeError(b.surface, dtheta, b.experiment);
      const double pct = e ? e->mean_pct : 0.0;
      const double sdis = t.sdis_in * (1.0 + Uniform(rng, pct / 100.0));
      const double theta = t.theta_rad + dtheta;
      if (!e || theta <= -kPi / 3.0 || theta >= kPi / 3.0) {
        ++out.rejected;
        continue;
      }
      width = ShortSideWidthT<double>(cam, sdis, theta, lj, rj, config.edges);
    }
    if (!std::isfinite(width) || width <= 0.0) {
      ++out.rejected;
      continue;
    }
    const double err = width - truth_width;
    out.errors_in.push_back(err);
    if (std::abs(err) <= config.tolerance_in) ++within;
  }
  const double n = static_cast<double>(out.errors_in.size());
  if (n > 0) {
    double sum = 0.0, sum2 = 0.0;
    for (double e : out.errors_in) sum += e;
    out.mean_error_in = sum / n;
    for (double e : out.errors_in) sum2 += (e - out.mean_error_in) * (e - out.mean_error_in);
    out.stddev_in = n > 1 ? std::sqrt(sum2 / (n - 1)) : 0.0;
  }
  out.p_within_tolerance = static_cast<double>(within) / config.trials;
  return R::Ok(std::move(out));
}

}  // namespace stickrep::sensing
