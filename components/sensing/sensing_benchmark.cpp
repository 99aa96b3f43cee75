// Speed of the width computation and of the Monte Carlo experiment (trials per second).
#include <benchmark/benchmark.h>

#include <random>

#include "sensing/error_analysis.h"
#include "sensing/landmark_estimator.h"

namespace stickrep::sensing {
namespace {

void BM_ShortSideWidth(benchmark::State& state) {
  const CameraModel cam;
  const SceneTruth t = *MakeScene(cam, {72.0, DegToRad(70.0), 36.0, 0.0});
  double theta = t.theta_rad;
  for (auto _ : state) {
    benchmark::DoNotOptimize(theta);
    benchmark::DoNotOptimize(ShortSideWidth(cam, t.sdis_in, theta, t.footprints));
  }
}
BENCHMARK(BM_ShortSideWidth);

void BM_TwoSideWidth(benchmark::State& state) {
  const CameraModel cam;
  const SceneTruth t = *MakeScene(cam, {72.0, DegToRad(70.0), 36.0, 0.0});
  double rl = t.rl_in;
  for (auto _ : state) {
    benchmark::DoNotOptimize(rl);
    benchmark::DoNotOptimize(TwoSideWidth(cam, rl, t.rr_in, t.footprints));
  }
}
BENCHMARK(BM_TwoSideWidth);

void BM_ShortSideGradient(benchmark::State& state) {
  const CameraModel cam;
  const SceneTruth t = *MakeScene(cam, {72.0, DegToRad(70.0), 36.0, 0.0});
  for (auto _ : state) {
    benchmark::DoNotOptimize(ShortSideGradient(cam, t.sdis_in, t.theta_rad, t.footprints,
                                               ShortSideEdges::kPaperSensorRays));
  }
}
BENCHMARK(BM_ShortSideGradient);

// Trials per second are reported as items/s.
void BM_MonteCarlo(benchmark::State& state) {
  const CameraModel cam;
  const Geometry g = state.range(0) == 0 ? Geometry::kShortSide : Geometry::kTwoSide;
  MonteCarloConfig cfg;
  cfg.trials = 100000;
  std::mt19937_64 rng(1);
  for (auto _ : state) {
    auto r = RunMonteCarlo(cam, {72.0, DegToRad(70.0), 36.0, 0.0}, g, cfg, rng);
    benchmark::DoNotOptimize(r);
  }
  state.SetItemsProcessed(state.iterations() * cfg.trials);
  state.SetLabel(ToString(g));
}
BENCHMARK(BM_MonteCarlo)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_LandmarkEstimate(benchmark::State& state) {
  const RobotConfig robot;
  const LandmarkEstimator est(robot);
  SonarScan scan;
  for (int k = 0; k < 24; ++k) {
    const auto d = ReturnedRange(est.ring(), 72.0, est.ring().BearingOf(k));
    scan.ranges_in.push_back(d.ok() && est.ring().InRange(*d) ? *d : 0.0);
    scan.valid.push_back(d.ok() && est.ring().InRange(*d));
  }
  const SceneTruth t = *MakeScene(est.camera(), {72.0, kPi / 2, 36.0, 0.0});
  const std::vector<JambCandidate> cands = {{{10.0, 20.0}, 0.9}, {t.footprints, 0.8}};
  for (auto _ : state) benchmark::DoNotOptimize(est.Estimate(scan, cands));
}
BENCHMARK(BM_LandmarkEstimate);

}  // namespace
}  // namespace stickrep::sensing

BENCHMARK_MAIN();
