// Speed of the vertical edge ribbon detector. The text's implementation took 100 ms per
// frame (§4.1.1 setting, Figure 4.1); the aim here is under 1 ms in five-row mode on a
// 512 x 480 frame.
#include <benchmark/benchmark.h>

#include <random>

#include "common/units.h"
#include "vision/ribbon_detector.h"
#include "world/camera_renderer.h"
#include "world/realism.h"
#include "world/world.h"

namespace stickrep::vision {
namespace {

constexpr std::uint64_t kSeed = 20240601;

// A rendered 512 x 480 frame of a closed 36 in door 6 ft away, next to a poster.
cv::Mat DoorFrame(double* range_in) {
  world::HallwayOptions options;
  options.width_in = 240.0;
  const world::Scene scene(world::MakeStraightHallway(
      {world::HallwayFeature::Wall(120), world::HallwayFeature::Door(36),
       world::HallwayFeature::Poster(60), world::HallwayFeature::Wall(120)},
      options));
  const world::CameraRenderer renderer{world::CameraModel{}};
  std::mt19937_64 rng(kSeed);
  const world::RenderedFrame frame = renderer.Render(scene, {150.0, 120.0 - 72.0, 0.0}, {}, rng);
  *range_in = frame.truth.axis_range_in;
  return frame.image;
}

void BM_Detect(benchmark::State& state) {
  double range_in = 0.0;
  const cv::Mat image = DoorFrame(&range_in);
  RibbonDetectorParams params;
  params.row_mode = state.range(0) == 0 ? RowMode::kFiveRows : RowMode::kFullFrame;
  const RibbonDetector detector(params);
  size_t pairs = 0;
  for (auto _ : state) {
    DetectResult result = detector.Detect(image, range_in);
    pairs = result.detection.pairs.size();
    benchmark::DoNotOptimize(result);
  }
  state.counters["pairs"] = static_cast<double>(pairs);
  state.SetLabel(state.range(0) == 0 ? "five rows" : "full frame");
}
BENCHMARK(BM_Detect)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// A cluttered frame (every realism feature on) 9 ft from a wall of three doors, with the
// head band in view: the appearance rule's every test runs.
void BM_DetectRealisticFrame(benchmark::State& state) {
  world::HallwayOptions options;
  options.width_in = 216.0;
  world::World w = world::MakeStraightHallway(
      {world::HallwayFeature::Wall(120), world::HallwayFeature::Door(36),
       world::HallwayFeature::Wall(30), world::HallwayFeature::Door(32),
       world::HallwayFeature::Wall(80), world::HallwayFeature::Door(36),
       world::HallwayFeature::Wall(120)},
      options);
  std::mt19937_64 rng(kSeed);
  const world::RealismOptions realism = world::FullRealism();
  world::ApplyRealism(realism, rng, &w);
  const world::CameraRenderer renderer(world::DrawCamera(realism, world::CameraModel{}, rng));
  const world::RenderedFrame frame =
      renderer.Render(world::Scene(w), {200.0, 0.0, 0.0},
                      world::DrawIllumination(realism, {}, rng), rng);
  const RibbonDetector detector;
  size_t pairs = 0;
  for (auto _ : state) {
    DetectResult result = detector.Detect(frame.image, frame.truth.axis_range_in);
    pairs = result.detection.pairs.size();
    benchmark::DoNotOptimize(result);
  }
  state.counters["pairs"] = static_cast<double>(pairs);
  state.SetLabel("five rows, cluttered");
}
BENCHMARK(BM_DetectRealisticFrame)->Unit(benchmark::kMicrosecond);

// A frame of uniform noise: the worst case for footprints and pairs (many clumps).
void BM_DetectNoiseFrame(benchmark::State& state) {
  cv::Mat image(480, 512, CV_8UC1);
  cv::RNG rng(kSeed);
  rng.fill(image, cv::RNG::UNIFORM, 0, 256);
  RibbonDetectorParams params;
  params.row_mode = state.range(0) == 0 ? RowMode::kFiveRows : RowMode::kFullFrame;
  const RibbonDetector detector(params);
  for (auto _ : state) {
    DetectResult result = detector.Detect(image, 72.0);
    benchmark::DoNotOptimize(result);
  }
  state.SetLabel(state.range(0) == 0 ? "five rows" : "full frame");
}
BENCHMARK(BM_DetectNoiseFrame)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace stickrep::vision

BENCHMARK_MAIN();
