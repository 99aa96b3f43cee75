#include "plot/bar_chart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace stickrep::plot {

namespace {

std::string Compact(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.4g", v);
  return buf;
}

void PutText(cv::Mat& img, const std::string& text, cv::Point at, double scale,
             bool centred = false) {
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &baseline);
  if (centred) at.x -= size.width / 2;
  cv::putText(img, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(20, 20, 20), 1,
              cv::LINE_AA);
}

}  // namespace

BarChart HistogramOf(const std::vector<double>& samples, double lo, double hi, int bins,
                     const std::string& title, const std::string& x_label,
                     const std::string& y_label) {
  if (bins <= 0 || !(hi > lo)) throw std::invalid_argument("HistogramOf: need bins > 0, hi > lo");
  BarChart chart{title, x_label, y_label, {}, std::vector<double>(bins, 0.0)};
  const double width = (hi - lo) / bins;
  for (int i = 0; i < bins; ++i) chart.labels.push_back(Compact(lo + (i + 0.5) * width));
  for (double s : samples) {
    if (std::isnan(s)) continue;
    const int b = std::clamp(static_cast<int>(std::floor((s - lo) / width)), 0, bins - 1);
    chart.values[b] += 1.0;
  }
  return chart;
}

BarChart IntegerHistogramOf(const std::vector<int>& samples, int lo, int hi,
                            const std::string& title, const std::string& x_label,
                            const std::string& y_label) {
  if (hi < lo) throw std::invalid_argument("IntegerHistogramOf: need hi >= lo");
  BarChart chart{title, x_label, y_label, {}, std::vector<double>(hi - lo + 1, 0.0)};
  for (int v = lo; v <= hi; ++v) chart.labels.push_back(std::to_string(v));
  for (int s : samples) chart.values[std::clamp(s, lo, hi) - lo] += 1.0;
  return chart;
}

void WriteBarChartPng(const BarChart& chart, const std::string& path, int width_px,
                      int height_px) {
  if (chart.labels.size() != chart.values.size() || chart.values.empty()) {
    throw std::invalid_argument("WriteBarChartPng: need one label per value and at least one");
  }
  cv::Mat img(height_px, width_px, CV_8UC3, cv::Scalar(255, 255, 255));
  const int left = 80, right = 20, top = 50, bottom = 70;
  const int plot_w = width_px - left - right, plot_h = height_px - top - bottom;
  const double vmax = std::max(1e-12, *std::max_element(chart.values.begin(), chart.values.end()));

  PutText(img, chart.title, {width_px / 2, 30}, 0.6, true);
  PutText(img, chart.x_label, {left + plot_w / 2, height_px - 15}, 0.5, true);
  PutText(img, chart.y_label, {8, top - 10}, 0.45);
  cv::line(img, {left, top}, {left, top + plot_h}, cv::Scalar(0, 0, 0));
  cv::line(img, {left, top + plot_h}, {left + plot_w, top + plot_h}, cv::Scalar(0, 0, 0));
  for (int t = 0; t <= 4; ++t) {
    const int y = top + plot_h - t * plot_h / 4;
    cv::line(img, {left - 4, y}, {left, y}, cv::Scalar(0, 0, 0));
    PutText(img, Compact(vmax * t / 4.0), {5, y + 4}, 0.4);
  }
  const int n = static_cast<int>(chart.values.size());
  const double bar_w = static_cast<double>(plot_w) / n;
  const int label_every = std::max(1, static_cast<int>(std::ceil(n * 40.0 / plot_w)));
  for (int i = 0; i < n; ++i) {
    const int x0 = left + static_cast<int>(i * bar_w) + 1;
    const int x1 = left + static_cast<int>((i + 1) * bar_w) - 1;
    const int h = static_cast<int>(std::round(chart.values[i] / vmax * plot_h));
    if (h > 0) {
      cv::rectangle(img, {x0, top + plot_h - h}, {std::max(x0, x1), top + plot_h},
                    cv::Scalar(180, 110, 40), cv::FILLED);
    }
    if (i % label_every == 0) {
      PutText(img, chart.labels[i], {(x0 + x1) / 2, top + plot_h + 18}, 0.38, true);
    }
  }
  if (!cv::imwrite(path, img)) throw std::runtime_error("cannot write PNG file " + path);
}

}  // namespace stickrep::plot
