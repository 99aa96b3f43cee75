#include "measure_tool/sample_frames.h"

#include <cstdio>
#include <functional>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <vector>

#include "common/input_error.h"
#include "common/units.h"
#include "landmark/landmark_pipeline.h"
#include "measure_tool/real_images.h"
#include "world/camera_renderer.h"
#include "world/realism.h"
#include "world/robot_models.h"
#include "world/scene.h"
#include "world/sonar_ring.h"

namespace stickrep::measure {
namespace {

// One sample: its name, the feature switched on, where the camera stands.
struct Sample {
  const char* name;
  std::function<void(world::RealismOptions*)> feature;
  double x_in;       // along the hallway, where the optical axis meets the wall square-on
  double range_in;   // camera to wall
  double stare_deg;  // optical axis turned from the wall normal (toward +x)
};

std::vector<Sample> Samples() {
  using O = world::RealismOptions;
  return {
      {"clean", [](O*) {}, 168.0, 72.0, 0.0},
      {"floor_reflections", [](O* o) { o->floor_reflections = true; }, 168.0, 108.0, 0.0},
      {"ceiling_lights", [](O* o) { o->ceiling_lights = true; }, 168.0, 200.0, 0.0},
      {"notice_boards",
       [](O* o) {
         o->notice_boards = true;
         o->notice_board_spacing_in = 30.0;
       },
       440.0, 72.0, 0.0},
      {"pilasters", [](O* o) { o->pilasters = true; }, 201.0, 120.0, 0.0},
      {"white_doors",
       [](O* o) {
         o->door_appearance = true;
         o->dark_door_share = 0.0;
         o->white_door_share = 1.0;
       },
       168.0, 72.0, 0.0},
      {"doors_ajar",
       [](O* o) {
         o->doors_ajar = true;
         o->ajar_share = 1.0;
       },
       168.0, 72.0, 0.0},
      {"oblique", [](O*) {}, 168.0, 72.0, 35.0},
      {"camera_and_light",
       [](O* o) {
         o->camera_misalignment = true;
         o->illumination = true;
       },
       168.0, 72.0, 0.0},
      {"all", [](O* o) { *o = world::FullRealism(); }, 201.0, 108.0, 10.0},
  };
}

world::World Hallway(double width_in) {
  using world::HallwayFeature;
  world::HallwayOptions options;
  options.width_in = width_in;
  return world::MakeStraightHallway(
      {HallwayFeature::Wall(150), HallwayFeature::Door(36), HallwayFeature::Wall(30),
       HallwayFeature::Door(32), HallwayFeature::Wall(300), HallwayFeature::Door(40),
       HallwayFeature::Wall(200)},
      options);
}

// The robot pose whose camera stands range_in from the wall (y = width/2), its optical
// axis turned stare_deg from the normal and meeting the wall at x_in.
world::Pose2d PoseFor(const Sample& s, const world::CameraModel& camera, double wall_y) {
  const double stare = DegToRad(s.stare_deg);
  const double cam_x = s.x_in - s.range_in * std::tan(stare);
  const double heading = DegToRad(90.0 - camera.mount_yaw_deg) - stare;
  return {cam_x, wall_y - s.range_in, heading};
}

}  // namespace

std::string WriteSampleFrames(const std::string& dir, const sensing::RobotConfig& robot,
                              std::uint64_t seed) {
  const world::RobotModels models = world::RobotModelsFromConfig(robot);
  const world::SonarRingSimulator sonar(models.sonar);
  const landmark::LandmarkPipeline pipeline(robot, vision::RibbonDetectorParams{},
                                            sensing::LandmarkEstimatorConfig{});
  const double hallway = 288.0;
  std::string report;
  for (const Sample& s : Samples()) {
    world::RealismOptions options = world::CleanRender();
    s.feature(&options);
    std::mt19937_64 rng(seed);
    world::World w = Hallway(hallway);
    world::ApplyRealism(options, rng, &w);
    const world::Scene scene(std::move(w));
    const world::CameraRenderer renderer(world::DrawCamera(options, models.camera, rng));
    const world::Illumination light = world::DrawIllumination(options, {}, rng);
    const world::Pose2d X_WR = PoseFor(s, models.camera, hallway / 2.0);
    const world::RenderedFrame frame = renderer.Render(scene, X_WR, light, rng);
    sensing::SonarScan scan;
    for (const world::SonarReading& r : sonar.SenseExact(scene, X_WR)) {
      scan.ranges_in.push_back(r.valid ? r.range_in : 0.0);
      scan.valid.push_back(r.valid);
    }
    const cv::Mat& img = frame.image;
    const vision::ImageView view{img.cols, img.rows, static_cast<int>(img.step), "mono8",
                                 img.data, img.total()};
    vision::RibbonDetection detection;
    const landmark::FrameOutcome out = pipeline.Process(view, scan, &detection);
    std::vector<sensing::JambCandidate> ranked = out.ranked;
    std::stable_sort(ranked.begin(), ranked.end(),
                     [](const auto& a, const auto& b) { return a.confidence > b.confidence; });
    std::vector<std::pair<double, double>> truth;
    for (const world::DoorTruth& d : frame.truth.doors) {
      if (d.both_jambs_visible) truth.push_back({d.left_column_px, d.right_column_px});
    }
    char caption[160];
    if (out.kind == landmark::FrameOutcome::Kind::kObservation) {
      std::snprintf(caption, sizeof(caption), "%s: door %s, %.1f in", s.name,
                    sensing::ToString(out.observation.door_class), out.observation.width_in);
    } else {
      std::snprintf(caption, sizeof(caption), "%s: no door", s.name);
    }
    const std::string path = dir + "/" + s.name + ".png";
    if (!cv::imwrite(path, DrawDetections(img, detection, ranked, truth, caption),
                     {cv::IMWRITE_PNG_COMPRESSION, 9})) {
      throw InputError(path, 0, "", "cannot write the sample frame");
    }
    report += path + "  " + caption + "\n";
  }
  return report;
}

}  // namespace stickrep::measure
