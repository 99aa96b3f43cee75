#pragma once

// The Figure 6.1 ambiguity analysis as a text report (mean, distribution, worst starts, the
// paper's no-error figure of Table 6.22 beside ours), as JSON and as a PNG histogram.

#include <nlohmann/json.hpp>
#include <string>

#include "stickrep/ambiguity.h"

namespace stickrep::map {

struct AmbiguityReportOptions {
  int worst = 10;        // how many worst starts to list
  double seconds = 0.0;  // run time of the analysis, printed when > 0
};

std::string FormatAmbiguityText(const Map& map, const AmbiguityOptions& options,
                                const AmbiguityResult& result,
                                const AmbiguityReportOptions& report = {});
nlohmann::json AmbiguityJson(const Map& map, const AmbiguityOptions& options,
                             const AmbiguityResult& result,
                             const AmbiguityReportOptions& report = {});
// Histogram of edges needed per start (Figure 6.1); throws std::runtime_error on write errors.
void WriteAmbiguityHistogramPng(const Map& map, const AmbiguityResult& result,
                                const std::string& path);

}  // namespace stickrep::map
