#pragma once

// The stickrep-study tool: runs the simulation study (study.h) over one or more maps, or the
// whole of Chapter 6 with --suite paper, and reports it in the layout of Tables 6.11–6.22
// with the dissertation's figures beside ours, histograms like Figures 6.3 and 6.5 as PNG,
// and every figure as JSON.

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "study_tool/study.h"

namespace stickrep::recovery::report {

// The five lines of Tables 6.11–6.21, as printed in the text.
struct PaperLines {
  const char* table;
  const char* caption;
  double with_error, recovered, not_converged, correct, incorrect;
};
// The text's table for this map and method, if it has one.
std::optional<PaperLines> PaperLinesFor(const std::string& map_name, const std::string& method);

// A row of Table 6.22.
struct PaperSummary {
  double edges, distance_ft, time_s, accuracy_pct;
};
std::optional<PaperSummary> PaperSummaryFor(const std::string& map_name, bool with_error);
// "Engr Bldg", "Wells Hall", ... (Table 6.22's labels), or the map name.
std::string DomainLabel(const std::string& map_name);

struct ToolOptions {
  std::vector<std::string> maps;
  std::string suite;                 // "" or "paper"
  std::vector<std::string> methods;  // ids; empty: no-error, deterministic, bayes
  int trials = 10;
  int runs = 1000;
  std::uint64_t seed = 1994;
  int threads = 0;               // 0: every core
  std::string error_model_path;  // "" : configs/error_model_paper.yaml
  std::string config_path;       // "" : configs/study.yaml
  std::vector<std::string> start_rings;  // ring ids runs start on; empty: every ring
  std::string json_path;
  std::string png_dir;
  bool progress = true;  // drawn only when stderr is a terminal
};

// The whole tool: loads, runs, prints. Returns the exit code: 0, or kExitBadInput (2) with
// file:line:key and the reason on `err` for bad input.
int RunTool(const ToolOptions& options, std::ostream& out, std::ostream& err);

// The report of one domain (tables of its methods beside the paper's).
void PrintDomain(std::ostream& out, const DomainResult& result, const StudyOptions& options);
// Table 6.22 over the domains studied, plus the Bayes filter beside deterministic recovery.
void PrintSummary(std::ostream& out, const std::vector<DomainResult>& results);

}  // namespace stickrep::recovery::report
