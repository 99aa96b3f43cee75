#pragma once

#include <string>
#include <vector>

namespace stickrep::plot {

// A bar chart to be written as a PNG: one bar per label, with a title and axis labels.
// Used for every histogram the tools write (ambiguity, Monte Carlo, study results).
struct BarChart {
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<std::string> labels;  // one per bar, printed under it (thinned if crowded)
  std::vector<double> values;       // bar heights, >= 0
};

// Bins `samples` into `bins` equal bins over [lo, hi); samples outside are clamped into the
// first or last bin so that nothing is silently lost. Labels are the bin centres.
BarChart HistogramOf(const std::vector<double>& samples, double lo, double hi, int bins,
                     const std::string& title, const std::string& x_label,
                     const std::string& y_label = "count");

// Bins integer samples one bar per value in [lo, hi] (clamped at both ends).
BarChart IntegerHistogramOf(const std::vector<int>& samples, int lo, int hi,
                            const std::string& title, const std::string& x_label,
                            const std::string& y_label = "count");

// Writes the chart; throws std::runtime_error if the file cannot be written.
void WriteBarChartPng(const BarChart& chart, const std::string& path, int width_px = 900,
                      int height_px = 520);

}  // namespace stickrep::plot
