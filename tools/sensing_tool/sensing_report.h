#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "plot/bar_chart.h"
#include "sensing/error_analysis.h"
#include "sensing/robot_config.h"

namespace stickrep::sensing {

// What the `stickrep-sensing report` reproduces and with which free parameters. The
// scene defaults (6 ft, 36 in door on the optical axis) are documented in docs/sensing.md.
struct ReportOptions {
  std::uint64_t seed = 19930501;
  int trials = 10000;              // §5.5: "Ten thousand trials at a given ... orientation"
  double wall_distance_in = 72.0;  // §4.1.1: the six-foot reference viewing range
  double door_width_in = 36.0;     // the most common class (Table 6.8)
  double door_offset_in = 0.0;     // door centred where the optical axis meets the wall
  ShortSideEdges edges = ShortSideEdges::kPaperSensorRays;
  ErrorBounds bounds;
};

// The report: text tables (ours beside the paper's), the same as JSON, and the histograms
// of Figures 5.4-5.9.
struct SensingReport {
  std::string text;
  nlohmann::json json;
  std::vector<std::pair<std::string, plot::BarChart>> figures;  // file name, chart
};

// Runs the linear model and the Monte Carlo experiment; throws std::runtime_error if a
// stare of the paper cannot be evaluated (a bug, not bad input).
SensingReport BuildSensingReport(const RobotConfig& robot, const ReportOptions& options);

// Writes every figure as DIR/<name>.png (creating DIR).
void WriteReportFigures(const SensingReport& report, const std::string& dir);

}  // namespace stickrep::sensing
