// Speed of the whole landmark pipeline on one rendered frame: detector (five rows), casing
// rule, Short Side geometry with the open-door check, Bayes classes.
#include <benchmark/benchmark.h>

#include <random>

#include "landmark/landmark_pipeline.h"
#include "sensing/robot_config.h"
#include "world/camera_renderer.h"
#include "world/robot_models.h"
#include "world/scene.h"
#include "world/sonar_ring.h"
#include "world/world.h"

namespace {

using namespace stickrep;

struct Fixture {
  world::RenderedFrame frame;
  sensing::SonarScan scan;
};

// A 36 in door at `range_in`, square-on, rendered once.
Fixture MakeFrame(double range_in, world::DoorState state) {
  world::HallwayOptions options;
  options.width_in = 2.0 * range_in + 48.0;
  const world::Scene scene(world::MakeStraightHallway(
      {world::HallwayFeature::Wall(120), world::HallwayFeature::Door(36, state, 1.4),
       world::HallwayFeature::Wall(240)},
      options));
  const world::RobotModels models = world::RobotModelsFromConfig(sensing::RobotConfig{});
  const world::Pose2d X_WR{138.0, options.width_in / 2.0 - range_in, 0.0};
  std::mt19937_64 rng(1);
  Fixture f;
  f.frame = world::CameraRenderer(models.camera).Render(scene, X_WR, {}, rng);
  for (const auto& r : world::SonarRingSimulator(models.sonar).SenseExact(scene, X_WR)) {
    f.scan.ranges_in.push_back(r.valid ? r.range_in : 0.0);
    f.scan.valid.push_back(r.valid);
  }
  return f;
}

void BM_LandmarkPipeline(benchmark::State& state) {
  const double range_in = static_cast<double>(state.range(0));
  const auto door = state.range(1) ? world::DoorState::kOpenInward : world::DoorState::kClosed;
  const Fixture f = MakeFrame(range_in, door);
  const landmark::LandmarkPipeline pipeline(sensing::RobotConfig{}, {}, {});
  const cv::Mat& img = f.frame.image;
  const vision::ImageView view{img.cols, img.rows, static_cast<int>(img.step),
                               "mono8",  img.data, img.total()};
  landmark::FrameOutcome out;
  for (auto _ : state) {
    out = pipeline.Process(view, f.scan);
    benchmark::DoNotOptimize(out);
  }
  state.SetLabel(out.kind == landmark::FrameOutcome::Kind::kObservation
                     ? std::string("door ") + sensing::ToString(out.observation.door_class)
                     : "no door");
}
// Args: range in inches, door open (1) or closed (0).
BENCHMARK(BM_LandmarkPipeline)->Args({72, 0})->Args({144, 0})->Args({72, 1});

}  // namespace

BENCHMARK_MAIN();
