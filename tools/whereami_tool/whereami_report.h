#pragma once

// stickrep-whereami: many seeded Where-am-I runs (whereami_run.h), one line each, and their
// summary beside the paper's Table 6.22.

#include <cstdint>
#include <ostream>
#include <map>
#include <string>
#include <vector>

#include "whereami/whereami_run.h"

namespace stickrep::whereami {

struct ToolOptions {
  std::string config_dir;          // empty: configs/
  std::string map_file;            // empty: system.yaml's
  std::string virtual_robot_file;  // empty: configs/virtual_robot.yaml
  std::uint64_t first_seed = 1;
  int runs = 20;
  int threads = 2;
  double max_sim_s = 600.0;
  double kidnap_after_s = -1.0;
  double kidnap_jump_in = 2500.0;
  bool kidnap_jump_random = false;  // RunOptions::kidnap_jump_random
  double keep_going_ft = 0.0;       // RunOptions::keep_going_ft
  bool reliability = false;         // print the published confidence's reliability table
  std::string json_path;           // empty: none
  bool trace = false;              // print each run's sensed and true edge sequences
  // Draw each run's true path over the map: <path_png>_seed<N>.png (empty: none).
  std::string path_png;
  // Rings to start on, run i on rings[i % size]; empty: the virtual robot's ring.
  std::vector<std::string> rings;
  // Measuring the assembled edges' errors over this much travel per run instead of
  // localizing (0: Where-am-I runs), and where to write them as an error model.
  double measure_ft = 0.0;
  std::string error_model_out;
  // Instead of runs: the batches' --json files pooled into one calibration
  // (calibration_fit.h).
  std::vector<std::string> fit_calibration;
};

// What the runs add up to.
struct Summary {
  int runs = 0;
  int localized = 0;
  int correct = 0;
  double mean_edges = 0.0;        // over localized runs
  double mean_distance_ft = 0.0;
  double mean_time_s = 0.0;
  int kidnapped = 0;
  int lost_detected = 0;
  int recovered_correct = 0;      // after the kidnap
  int collisions = 0;
  std::map<Ending, int> endings;  // runs by how they ended
  int start_redraws = 0;          // starts refused and drawn again, over all runs
  double max_offset_in = 0.0;
  double max_heading_deg = 0.0;
  int left_ring = 0;  // runs that travelled outside the start ring's hallway
};
Summary Summarize(const std::vector<RunResult>& results);

// Runs the seeds on `threads` workers; results in seed order.
std::vector<RunResult> RunSeeds(const RunSetup& setup, const ToolOptions& options);

// The tool: prints a line per run and the summary; 0 on success, 2 on bad input (with the
// message on `err`).
int RunTool(const ToolOptions& options, std::ostream& out, std::ostream& err);

}  // namespace stickrep::whereami
