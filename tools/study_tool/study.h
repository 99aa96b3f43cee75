#pragma once

// The simulation study of Chapter 6 (Figure 6.2, §6.3–§6.8) over one map: T trials of N
// runs; each run starts at a random place and direction, senses the true edges through
// the error model (sensed_stream.h) and feeds them, edge by edge, to each method under
// study — the recovery strategies and the Bayes filter all read the same sensed edges of
// the same run — until the method reports one pose, fails, or the run gives up.
//
// Outcomes of one run (the lines of Tables 6.11–6.21):
//   correct        one candidate, and its edge and direction are the truth
//   incorrect      one candidate elsewhere (false confidence, §6.6)
//   not converged  the strategy failed (no heuristic could recover), or max_edges sensed
//                  edges without a unique pose, or an open ring ended
//   with error     some sensed edge read before the run ended was not faithful (a false,
//                  missed or mis-sized door, or a wall outside the level-0 tolerance)
//   recovered      a run with error that ended with the correct pose
// Edges are all sensed edges the run read, over every restarted sequence; distance is the
// true travel from the start point to the far end of the last edge, in whole frames
// (2.6 ft/s x 0.2 s = 6.24 in per frame); time is frames x 0.2 s.

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "recovery/error_model.h"
#include "recovery/pose_recovery.h"
#include "stickrep/map.h"

namespace stickrep::recovery {

// One method under study.
struct MethodSpec {
  enum class Kind { kStrategy, kBayes } kind = Kind::kStrategy;
  Strategy strategy = Strategy::kDeterministic;
  bool error_free = false;  // run on error-free sensing with exact matching (§6.4.1)
  std::string Id() const;   // "no-error", "deterministic", "bayes", ...
};

enum class Outcome : std::uint8_t { kCorrect, kIncorrect, kNotConverged };

struct RunResult {
  Outcome outcome = Outcome::kNotConverged;
  bool had_error = false;
  std::uint16_t edges = 0;
  std::uint16_t restarts = 0;
  float travel_in = 0;  // rounded up to whole frames
};

// One trial's figures, in the layout of Tables 6.11–6.21 and 6.22.
struct TrialSummary {
  int runs = 0;
  double pct_with_error = 0;
  double pct_recovered = 0;  // of the runs with error
  double pct_not_converged = 0;
  double pct_correct = 0;
  double pct_incorrect = 0;
  // Over the runs that ended with a pose:
  double mean_edges = 0;
  double mean_distance_ft = 0;  // travelled, whole frames
  double mean_time_s = 0;
  double mean_restarts = 0;
};

struct ExperimentResult {
  MethodSpec method;
  std::vector<TrialSummary> trials;
  int median_trial = 0;         // the trial reported (median of the error share, or of the edges)
  TrialSummary all;             // every run of every trial together
  std::vector<RunResult> runs;  // trial-major, trials x runs
  const TrialSummary& median() const { return trials[median_trial]; }
};

struct StudyOptions {
  int trials = 10;
  int runs = 1000;
  std::uint64_t seed = 1994;
  int threads = 2;
  std::vector<MethodSpec> methods;
  ErrorModel error_model;
  StudyConfig config;
  // Ids of the rings a run may start on; empty: every ring of the map (the text's starts,
  // §6.3). A robot switched on in one hallway is studied by naming that hallway's ring.
  std::vector<std::string> start_rings;
  // Called from the calling thread about every 100 ms with (runs done, runs in total).
  std::function<void(std::uint64_t, std::uint64_t)> progress;
};

struct DomainResult {
  std::string map_name;
  int map_edges = 0;
  double mean_edge_metric_in = 0;
  std::vector<ExperimentResult> experiments;
  double seconds = 0;
  const ExperimentResult* Find(const std::string& id) const;
};

// Runs every method of `options` on `map`. Throws std::invalid_argument for a map with no
// edges, T or N of zero, a start ring the map does not have, or a bad error model / config. The
// result depends only on the map, the options and the seed — not on the number of threads.
DomainResult RunStudy(const map::Map& map, const StudyOptions& options);

// Summary of one trial's runs.
TrialSummary Summarise(const RunResult* runs, int count, double speed_ftps);

}  // namespace stickrep::recovery
