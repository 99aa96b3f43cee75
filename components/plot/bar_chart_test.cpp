#include "plot/bar_chart.h"

#include <gtest/gtest.h>

#include <filesystem>

#include <opencv2/imgcodecs.hpp>

namespace stickrep::plot {
namespace {

TEST(BarChartTest, HistogramClampsOutliersIntoEndBins) {
  const BarChart c = HistogramOf({-5.0, 0.1, 0.9, 1.5, 99.0}, 0.0, 2.0, 2, "t", "x");
  ASSERT_EQ(c.values.size(), 2u);
  EXPECT_DOUBLE_EQ(c.values[0], 3.0);
  EXPECT_DOUBLE_EQ(c.values[1], 2.0);
  EXPECT_EQ(c.labels[0], "0.5");
}

TEST(BarChartTest, IntegerHistogramHasOneBarPerValue) {
  const BarChart c = IntegerHistogramOf({1, 2, 2, 3, 7}, 1, 4, "t", "edges");
  ASSERT_EQ(c.values.size(), 4u);
  EXPECT_DOUBLE_EQ(c.values[1], 2.0);
  EXPECT_DOUBLE_EQ(c.values[3], 1.0);  // 7 clamped into the last bar
}

TEST(BarChartTest, WritesAReadablePngOfTheRequestedSize) {
  const std::string path = ::testing::TempDir() + "/bar_chart_test.png";
  WriteBarChartPng(IntegerHistogramOf({1, 2, 2, 3}, 1, 3, "title", "x"), path, 400, 300);
  const cv::Mat img = cv::imread(path);
  ASSERT_FALSE(img.empty());
  EXPECT_EQ(img.cols, 400);
  EXPECT_EQ(img.rows, 300);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace stickrep::plot
