// stickrep-sensing: reproduces the sensing tables of Chapter 5 (Tables 5.2-5.6, Figures
// 5.4-5.9) beside the paper's figures.
#include <CLI/CLI.hpp>
#include <fstream>
#include <iostream>
#include <optional>

#include "common/input_error.h"
#include "common/tool_main.h"
#include "sensing/robot_config.h"
#include "sensing_tool/sensing_report.h"

int main(int argc, char** argv) {
  using namespace stickrep::sensing;
  CLI::App app{"StickRep sensing geometry: error analysis and Monte Carlo (Chapter 5)"};
  app.require_subcommand(1);
  CLI::App* report =
      app.add_subcommand("report", "print Tables 5.2-5.6 and 4.1, ours beside the paper's");
  ReportOptions opt;
  std::string robot_path = DefaultRobotConfigPath();
  std::string json_path, png_dir;
  bool fov_edges = false;
  report->add_option("--robot", robot_path, "robot geometry YAML")->capture_default_str();
  report->add_option("--seed", opt.seed, "seed of the Monte Carlo generator")
      ->capture_default_str();
  report->add_option("--trials", opt.trials, "trials per stare and geometry")
      ->check(CLI::Range(1, 100000000))
      ->capture_default_str();
  report->add_option("--wall-distance-in", opt.wall_distance_in, "perpendicular range to the wall")
      ->check(CLI::Range(12.0, 420.0))
      ->capture_default_str();
  report->add_option("--door-width-in", opt.door_width_in, "true door width")
      ->check(CLI::Range(12.0, 96.0))
      ->capture_default_str();
  report
      ->add_option("--door-offset-in", opt.door_offset_in,
                   "door centre along the wall from the optical axis")
      ->check(CLI::Range(-60.0, 60.0))
      ->capture_default_str();
  report->add_flag("--fov-edges", fov_edges,
                   "Short Side sides along the FOV edges instead of the 30 deg rays");
  report->add_option("--json", json_path, "also write the report as JSON");
  report->add_option("--png", png_dir,
                     "write the histograms (Figures 5.4-5.9) into this directory");
  if (const std::optional<int> rc = stickrep::ParseCommandLine(app, argc, argv)) return *rc;

  try {
    const RobotConfig robot = LoadRobotConfigFile(robot_path);
    if (fov_edges) opt.edges = ShortSideEdges::kFieldOfViewEdges;
    const SensingReport rep = BuildSensingReport(robot, opt);
    std::cout << rep.text;
    if (!json_path.empty()) {
      std::ofstream f(json_path);
      if (!f) throw stickrep::InputError(json_path, 0, "--json", "cannot open for writing");
      f << rep.json.dump(2) << "\n";
    }
    if (!png_dir.empty()) WriteReportFigures(rep, png_dir);
  } catch (const stickrep::InputError& e) {
    std::cerr << "stickrep-sensing: " << e.what() << "\n";
    return stickrep::kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "stickrep-sensing: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
