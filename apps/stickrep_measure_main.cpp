// stickrep-measure: measures the landmark pipeline (detector, casing rule, geometry, Bayes
// classes) on rendered frames of the shipped maps, prints Table 6.10 ours beside the paper's
// and writes the measured error model for the simulation study (--error-model FILE there).
#include <CLI/CLI.hpp>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "common/input_error.h"
#include "common/tool_main.h"
#include "measure_tool/error_measurement.h"
#include "measure_tool/real_images.h"
#include "measure_tool/sample_frames.h"
#include "sensing/robot_config.h"
#include "common/config_paths.h"
#include "stickrep/map_io.h"

int main(int argc, char** argv) {
  using namespace stickrep;
  CLI::App app{"Measure the landmark pipeline on rendered frames (Table 6.10, SPEC 5)"};
  measure::MeasureConfig config;
  const std::string maps_dir = DataDir() + "/maps/";
  std::vector<std::string> map_paths;
  for (const char* name : {"engineering_building_3f", "wells_hall_7f", "wells_hall_7f_modified",
                           "regular_polygon_46", "storefront"}) {
    map_paths.push_back(maps_dir + name + ".yaml");
  }
  std::string robot_path = sensing::DefaultRobotConfigPath();
  std::string out_path = "measured_error_model.yaml";
  bool fov_edges = false, no_casing_rule = false;
  app.add_option("--maps", map_paths, "map files (frame i is drawn on map i mod count)")
      ->capture_default_str();
  app.add_option("--robot", robot_path, "robot geometry YAML")->capture_default_str();
  app.add_option("--seed", config.seed, "seed; frame i uses a generator seeded by (seed, i)")
      ->capture_default_str();
  app.add_option("--frames", config.frames, "frames to render")
      ->check(CLI::Range(1, 10000000))
      ->capture_default_str();
  app.add_option("--threads", config.threads, "worker threads (results do not depend on it)")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  app.add_option("--out", out_path, "measured error model YAML to write")->capture_default_str();
  app.add_option("--hallway-width-in", config.hallway_width_in,
                 "wall to opposite wall; the axis is half of it from the mapped wall")
      ->check(CLI::Range(48.0, 600.0))
      ->capture_default_str();
  app.add_option("--envelope-share", config.envelope_share,
                 "share of frames inside the 6.4.2 navigation envelope")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  app.add_option("--door-aim-share", config.door_aim_share,
                 "share of frames aimed at a door (the rest anywhere along the ring)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  app.add_option("--open-door-fraction", config.open_door_fraction,
                 "share of doors open in the open-door worlds")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  app.add_option("--max-roll-deg", config.max_roll_deg, "largest camera roll")
      ->check(CLI::Range(0.0, 20.0))
      ->capture_default_str();
  app.add_flag("--fov-edges", fov_edges,
               "Short Side sides along the FOV edges instead of the printed 30 deg rays");
  app.add_flag("--no-casing-rule", no_casing_rule,
               "classify the detector's pairs as they come (shows the casing problem)");
  bool realism = false, before = false;
  app.add_flag("--realism", realism,
               "cluttered, real-looking hallways: every world::RealismOptions feature on");
  app.add_flag("--detector-before", before,
               "the detector and pipeline as first built (for before/after figures)");
  app.add_option("--min-confidence", config.estimator.min_confidence,
                 "candidates below this detector confidence are not classified (4.1.2)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  app.add_option("--outside-stare-deg", config.outside_stare_deg,
                 "largest stare of the frames outside the envelope (oblique views)")
      ->check(CLI::Range(7.5, 45.0))
      ->capture_default_str();

  // stickrep-measure images FILE...: the detector on real frames.
  measure::ImageRunConfig images;
  CLI::App* images_cmd = app.add_subcommand(
      "images", "run the detector on image files (any size, made 512 x 480 mono8)");
  images_cmd->add_option("files", images.files, "PNG or JPEG files")->required();
  images_cmd->add_option("--range-in", images.range_in, "coaxial range (§4.1.1: six feet)")
      ->check(CLI::Range(12.0, 420.0))
      ->capture_default_str();
  images_cmd->add_option("--max-stare-deg", images.max_stare_deg,
                         "stares admitted by the width gate")
      ->check(CLI::Range(0.0, 55.0))
      ->capture_default_str();
  images_cmd->add_option("--annotations", images.annotations,
                         "true jamb columns: lines 'NAME: LJ RJ ...' or 'NAME: -'");
  images_cmd->add_option("--draw", images.draw_dir, "write each frame, detections drawn, here");
  images_cmd->add_option("--top", images.top, "pairs printed per image")
      ->check(CLI::Range(1, 32))
      ->capture_default_str();
  // stickrep-measure samples --out-dir DIR: one drawn frame per clutter class.
  std::string samples_dir;
  CLI::App* samples_cmd =
      app.add_subcommand("samples", "write a drawn frame of each clutter class (docs/vision.md)");
  samples_cmd->add_option("--out-dir", samples_dir, "folder for the PNGs")->required();
  if (const std::optional<int> rc = ParseCommandLine(app, argc, argv)) return *rc;

  try {
    if (images_cmd->parsed() || samples_cmd->parsed()) {
      const sensing::RobotConfig robot = sensing::LoadRobotConfigFile(robot_path);
      if (images_cmd->parsed()) {
        std::cout << measure::RunOnImages(images, robot);
      } else {
        std::cout << "seed " << config.seed << "\n"
                  << measure::WriteSampleFrames(samples_dir, robot, config.seed);
      }
      return 0;
    }
    if (realism) config.realism = world::FullRealism();
    if (before) measure::UseDetectorBeforeIssue17(&config);
    if (fov_edges) config.estimator.short_side_edges = sensing::ShortSideEdges::kFieldOfViewEdges;
    config.casing.enabled = !no_casing_rule;
    const sensing::RobotConfig robot = sensing::LoadRobotConfigFile(robot_path);
    std::vector<map::Map> maps;
    for (const std::string& path : map_paths) maps.push_back(map::LoadMap(path));
    std::ofstream out(out_path);
    if (!out) throw InputError(out_path, 0, "--out", "cannot open for writing");
    std::cout << "seed " << config.seed << "\n" << std::flush;
    const measure::Measurement m = measure::MeasurePipeline(maps, robot, config);
    std::cout << measure::FormatReport(m);
    out << measure::FormatErrorModelYaml(m);
    if (!out) throw std::runtime_error("cannot write " + out_path);
    std::cout << "error model written to " << out_path << "\n";
  } catch (const InputError& e) {
    std::cerr << "stickrep-measure: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::invalid_argument& e) {
    std::cerr << "stickrep-measure: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "stickrep-measure: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
