// Speed of the simulated world: a virtual robot needs a 512 x 480 frame well inside 33 ms
// to run at 30 frames per second, and a full sonar ring sweep per cycle.
#include <benchmark/benchmark.h>

#include <random>

#include "common/units.h"
#include "world/camera_renderer.h"
#include "world/realism.h"
#include "world/sonar_ring.h"
#include "world/world.h"

namespace stickrep::world {
namespace {

constexpr std::uint64_t kSeed = 20240601;

// `doors` doors of 36 in between 60 in walls, alternating closed / open, with posters.
Scene Hallway(int doors) {
  std::vector<HallwayFeature> features;
  for (int i = 0; i < doors; ++i) {
    features.push_back(i % 3 == 2 ? HallwayFeature::Poster(60) : HallwayFeature::Wall(60));
    features.push_back(HallwayFeature::Door(
        36, i % 2 == 0 ? DoorState::kClosed : DoorState::kOpenInward, DegToRad(70.0)));
  }
  features.push_back(HallwayFeature::Wall(60));
  return Scene(MakeStraightHallway(features));
}

void BM_RenderFrame(benchmark::State& state) {
  const Scene scene = Hallway(static_cast<int>(state.range(0)));
  CameraModel camera;
  camera.roll_deg = static_cast<double>(state.range(1));
  RenderOptions options;
  options.supersample = static_cast<int>(state.range(2));
  const CameraRenderer renderer(camera, options);
  std::mt19937_64 rng(kSeed);
  double x = 30.0;
  for (auto _ : state) {
    // 6.24 in per frame: one frame per 0.2 s at 2.6 ft/s (SPEC §8).
    RenderedFrame frame = renderer.Render(scene, {x, 0.0, 0.0}, {}, rng);
    benchmark::DoNotOptimize(frame.image.data);
    x += 6.24;
    if (x > 96.0 * state.range(0)) x = 30.0;
  }
  state.counters["panels"] = static_cast<double>(scene.panels().size());
  state.counters["fps"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
// Args: doors in the hallway, roll in degrees, horizontal supersampling.
BENCHMARK(BM_RenderFrame)
    ->Args({3, 0, 4})
    ->Args({3, 10, 4})
    ->Args({3, 0, 1})
    ->Args({200, 0, 4})
    ->Unit(benchmark::kMillisecond);

// The same drive with every realism feature on: lights, a glossy floor, boards, pilasters.
void BM_RenderRealisticFrame(benchmark::State& state) {
  const int doors = static_cast<int>(state.range(0));
  std::vector<HallwayFeature> features;
  for (int i = 0; i < doors; ++i) {
    features.push_back(HallwayFeature::Wall(i % 2 == 0 ? 30 : 90));
    features.push_back(HallwayFeature::Door(36));
  }
  features.push_back(HallwayFeature::Wall(60));
  World w = MakeStraightHallway(features);
  std::mt19937_64 rng(kSeed);
  const RealismOptions realism = FullRealism();
  ApplyRealism(realism, rng, &w);
  const Scene scene(std::move(w));
  const CameraRenderer renderer(DrawCamera(realism, CameraModel{}, rng));
  double x = 30.0;
  for (auto _ : state) {
    const Illumination light = DrawIllumination(realism, {}, rng);
    RenderedFrame frame = renderer.Render(scene, {x, 0.0, 0.0}, light, rng);
    benchmark::DoNotOptimize(frame.image.data);
    x += 6.24;
    if (x > 96.0 * doors) x = 30.0;
  }
  state.counters["panels"] = static_cast<double>(scene.panels().size());
}
BENCHMARK(BM_RenderRealisticFrame)->Arg(3)->Arg(200)->Unit(benchmark::kMillisecond);

void BM_SonarRing(benchmark::State& state) {
  const Scene scene = Hallway(static_cast<int>(state.range(0)));
  const SonarRingSimulator ring;
  double x = 30.0;
  for (auto _ : state) {
    auto readings = ring.SenseExact(scene, {x, 0.0, 0.0});
    benchmark::DoNotOptimize(readings.data());
    x += 6.24;
    if (x > 96.0 * state.range(0)) x = 30.0;
  }
  state.counters["panels"] = static_cast<double>(scene.panels().size());
}
BENCHMARK(BM_SonarRing)->Arg(3)->Arg(200)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace stickrep::world

BENCHMARK_MAIN();
