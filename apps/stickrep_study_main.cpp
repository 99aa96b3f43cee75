// stickrep-study: the Chapter 6 simulation study (Figure 6.2) on any map, or all of it with
// --suite paper.
#include <CLI/CLI.hpp>
#include <iostream>
#include <optional>

#include "common/input_error.h"
#include "common/tool_main.h"
#include "study_tool/study_report.h"

int main(int argc, char** argv) {
  stickrep::recovery::report::ToolOptions o;
  CLI::App app{"StickRep simulation study: pose recovery with sensing error (Chapter 6)"};
  app.add_option("MAP", o.maps, "Map files");
  app.add_option("--suite", o.suite, "'paper': every domain and strategy of Chapter 6");
  app.add_option("--methods", o.methods,
                 "no-error, none, relaxation, first-frame, false-door, missized, full-suite, "
                 "deterministic, bayes (default: no-error deterministic bayes)")
      ->delimiter(',');
  app.add_option("--trials,-T", o.trials, "Trials per experiment (default 10)")
      ->check(CLI::Range(1, 1000));
  app.add_option("--runs,-N", o.runs, "Runs per trial (default 1000)")
      ->check(CLI::Range(1, 10000000));
  app.add_option("--seed", o.seed, "Seed of the whole study");
  app.add_option("--threads", o.threads, "Worker threads (0: every core)")
      ->check(CLI::Range(0, 256));
  app.add_option("--error-model", o.error_model_path,
                 "Error model file (default configs/error_model_paper.yaml)");
  app.add_option("--config", o.config_path, "Study settings (default configs/study.yaml)");
  app.add_option("--start-ring", o.start_rings,
                 "Start runs only beside edges of this ring (repeatable; default: every ring)");
  app.add_option("--json", o.json_path, "Write every figure as JSON");
  app.add_option("--png-dir", o.png_dir, "Write histograms (Figures 6.3, 6.5) as PNG here");
  bool no_progress = false;
  app.add_flag("--no-progress", no_progress, "No progress bar");
  if (const std::optional<int> rc = stickrep::ParseCommandLine(app, argc, argv)) return *rc;
  o.progress = !no_progress;
  return stickrep::recovery::report::RunTool(o, std::cout, std::cerr);
}
