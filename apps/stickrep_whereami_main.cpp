// stickrep-whereami: seeded Where-am-I runs of the whole stack's components in one process,
// each judged against the simulated truth, and their summary beside Table 6.22.
#include <CLI/CLI.hpp>
#include <iostream>
#include <optional>

#include "common/input_error.h"
#include "common/tool_main.h"
#include "whereami_tool/whereami_report.h"

int main(int argc, char** argv) {
  stickrep::whereami::ToolOptions o;
  CLI::App app{"StickRep Where-am-I runs: recover the pose from seeded random starts"};
  app.add_option("--config-dir", o.config_dir, "Configuration directory (default configs/)");
  app.add_option("--map", o.map_file, "Map file (default: system.yaml's)");
  app.add_option("--virtual-robot", o.virtual_robot_file,
                 "Virtual robot settings (default configs/virtual_robot.yaml)");
  app.add_option("--seed", o.first_seed, "First seed (runs use seed, seed + 1, ...)");
  app.add_option("--runs,-N", o.runs, "Number of runs (default 20)")->check(CLI::Range(1, 100000));
  app.add_option("--threads", o.threads, "Worker threads (default 2)")->check(CLI::Range(1, 64));
  app.add_option("--max-sim-s", o.max_sim_s, "Give a run up after this much simulated time")
      ->check(CLI::Range(1.0, 36000.0));
  app.add_option("--kidnap-after", o.kidnap_after_s,
                 "Kidnap the robot this long (s) after the pose is recovered; -1: never")
      ->check(CLI::Range(-1.0, 3600.0));
  auto* jump =
      app.add_option("--kidnap-jump", o.kidnap_jump_in, "How far along the ring the kidnap moves it (in)");
  app.add_flag("--kidnap-jump-random", o.kidnap_jump_random,
               "Draw each run's kidnap jump from its seed over the middle 80 % of the ring")
      ->excludes(jump);
  app.add_option("--keep-going-ft", o.keep_going_ft,
                 "Without a kidnap: keep travelling this far after the pose, watching it")
      ->check(CLI::Range(0.0, 100000.0));
  app.add_flag("--reliability", o.reliability,
               "Print how often poses published with each confidence were right");
  app.add_option("--json", o.json_path, "Write every run as JSON");
  app.add_option("--ring", o.rings, "Ring(s) to start on (default: the virtual robot's)");
  app.add_option("--measure-ft", o.measure_ft,
                 "Measure the assembled edges' errors over this much travel per run instead")
      ->check(CLI::Range(1.0, 100000.0));
  app.add_option("--write-error-model", o.error_model_out,
                 "With --measure-ft: write the measured rates as an error model file");
  app.add_flag("--trace", o.trace,
               "Print each run's sensed edges beside the map edges passed, its behaviour and "
               "belief changes, and where the base touched a wall");
  app.add_option("--path-png", o.path_png,
                 "Draw each run's true path over the map into PREFIX_seed<N>.png");
  app.add_option("--fit-calibration", o.fit_calibration,
                 "Instead of runs: pool the published confidences of these --json batches (run "
                 "under one calibration) into one Platt fit, and print the calibration it makes");
  if (const std::optional<int> rc = stickrep::ParseCommandLine(app, argc, argv)) return *rc;
  return stickrep::whereami::RunTool(o, std::cout, std::cerr);
}
