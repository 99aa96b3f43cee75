#include "vision/ribbon_detector.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <random>
#include <vector>

#include "common/units.h"

namespace stickrep::vision {
namespace {

using ::testing::DoubleNear;
using ::testing::ElementsAre;
using ::testing::IsEmpty;
using ::testing::SizeIs;

// A light frame with a dark vertical band from column `left` to `right` (band edges at the
// pixel boundaries left - 0.5 and right + 0.5).
cv::Mat Band(int left, int right, int light = 180, int dark = 90) {
  cv::Mat image(480, 512, CV_8UC1, cv::Scalar(light));
  image.colRange(left, right + 1).setTo(cv::Scalar(dark));
  return image;
}

TEST(PrewittRowTest, StepOfNGreyLevelsPeaksAtN) {
  const cv::Mat image = Band(100, 511, 200, 150);
  std::vector<float> out(512);
  PrewittRow(image.data, image.cols, image.step[0], 240, out.data());
  EXPECT_FLOAT_EQ(out[99], -50.0f);
  EXPECT_FLOAT_EQ(out[100], -50.0f);
  EXPECT_FLOAT_EQ(out[98], -50.0f * 2.0f / 3.0f);
  EXPECT_FLOAT_EQ(out[50], 0.0f);
}

TEST(PrewittRowTest, MatchesOpenCvFilter2DWithThe5x5Kernel) {
  cv::Mat image(40, 64, CV_8UC1);
  cv::RNG rng(5);
  rng.fill(image, cv::RNG::UNIFORM, 0, 256);
  cv::Mat kernel(5, 5, CV_32F);
  for (int r = 0; r < 5; ++r) {
    const float row[5] = {-2, -1, 0, 1, 2};
    for (int c = 0; c < 5; ++c) kernel.at<float>(r, c) = row[c] / 15.0f;
  }
  cv::Mat expected;
  cv::filter2D(image, expected, CV_32F, kernel, cv::Point(-1, -1), 0, cv::BORDER_CONSTANT);
  std::vector<float> out(64);
  for (int row : {2, 17, 37}) {
    PrewittRow(image.data, image.cols, image.step[0], row, out.data());
    for (int c = 2; c < 62; ++c) {
      ASSERT_NEAR(out[c], expected.at<float>(row, c), 1e-3) << "row " << row << " col " << c;
    }
  }
}

TEST(SampledRowsTest, WithinSixFeetUsesTheFixedFiveRows) {
  // Outer rows at 0.45 of half the height: 108 px from the centre row 239.5.
  const RibbonDetector detector;
  EXPECT_THAT(detector.SampledRows(480, 72.0), ElementsAre(132, 232, 240, 248, 348));
  EXPECT_THAT(detector.SampledRows(480, 30.0), ElementsAre(132, 232, 240, 248, 348));
}

TEST(SampledRowsTest, BeyondSixFeetOuterRowsMoveInAsOneOverRange) {
  const RibbonDetector detector;
  EXPECT_THAT(detector.SampledRows(480, 144.0), ElementsAre(186, 232, 240, 248, 294));
  const std::vector<int> far = detector.SampledRows(480, 420.0);
  ASSERT_THAT(far, SizeIs(5));
  EXPECT_EQ(far[0], 240 - 19);  // 108 * 72 / 420 = 18.5 px
}

TEST(SampledRowsTest, TheOuterRowsStayOnADoorTwiceAsFarAsTheRange) {
  // A door 80 in tall seen from a camera 40 in up: at twice the range the rows must still
  // cut it above a 6 in baseboard and below its top (real frames: rows on the floor's
  // reflections and the ceiling lights when the range was off).
  const RibbonDetector detector;
  const double f = 256.0 / std::tan(DegToRad(55.817) / 2.0);
  for (double range : {36.0, 72.0, 144.0, 288.0}) {
    const std::vector<int> rows = detector.SampledRows(480, range);
    const double far = 2.0 * range;
    const double top_in = 40.0 + (239.5 - rows.front()) * far / f;
    const double bottom_in = 40.0 - (rows.back() - 239.5) * far / f;
    EXPECT_LT(top_in, 80.0) << range;
    EXPECT_GT(bottom_in, 6.0) << range;
  }
}

TEST(RibbonDetectorTest, DarkBandGivesTwoSubPixelFootprintsAndOnePair) {
  const RibbonDetector detector;
  const DetectResult result = detector.Detect(Band(200, 259), 72.0);
  ASSERT_TRUE(result.ok()) << result.message;
  ASSERT_THAT(result.detection.footprints, SizeIs(2));
  EXPECT_THAT(result.detection.footprints[0].column_px, DoubleNear(199.5, 0.05));
  EXPECT_THAT(result.detection.footprints[1].column_px, DoubleNear(259.5, 0.05));
  EXPECT_EQ(result.detection.footprints[0].polarity, -1);
  EXPECT_EQ(result.detection.footprints[1].polarity, 1);
  EXPECT_EQ(result.detection.footprints[0].rows_hit, 5);
  ASSERT_THAT(result.detection.pairs, SizeIs(1));
  EXPECT_THAT(result.detection.pairs[0].width_px, DoubleNear(60.0, 0.1));
}

TEST(RibbonDetectorTest, ThinLineGivesOneFootprintCentredOnIt) {
  cv::Mat image(480, 512, CV_8UC1, cv::Scalar(120));
  image.col(300).setTo(cv::Scalar(220));
  const DetectResult result = RibbonDetector().Detect(image, 72.0);
  ASSERT_TRUE(result.ok());
  ASSERT_THAT(result.detection.footprints, SizeIs(1));
  EXPECT_THAT(result.detection.footprints[0].column_px, DoubleNear(300.0, 1e-9));
}

TEST(RibbonDetectorTest, ThinLineIsMarkedALineAndAStepIsNot) {
  cv::Mat image = Band(100, 511, 70, 125);         // a dark casing, then a leaf from column 100
  image.colRange(300, 303).setTo(cv::Scalar(40));  // a 3 px seam on the leaf
  RibbonDetectorParams seams;
  seams.seam_lines = true;
  const DetectResult result = RibbonDetector(seams).Detect(image, 60.0);
  ASSERT_TRUE(result.ok()) << result.message;
  ASSERT_THAT(result.detection.footprints, SizeIs(2));
  EXPECT_FALSE(result.detection.footprints[0].line);  // the step from casing to leaf
  EXPECT_TRUE(result.detection.footprints[1].line);
  EXPECT_THAT(result.detection.footprints[1].column_px, DoubleNear(301.0, 1.5));
  // The leaf between them is a face framed by the casing and the seam: the pair scores as
  // one of opposite polarity with the seam's level as its right flank.
  ASSERT_THAT(result.detection.pairs, SizeIs(1));
  const CandidatePair& leaf = result.detection.pairs[0];
  EXPECT_THAT(leaf.right_flank, DoubleNear(40.0, 5.0));
  const DetectResult before = RibbonDetector().Detect(image, 60.0);  // every edge a step
  ASSERT_TRUE(before.ok());
  ASSERT_THAT(before.detection.pairs, SizeIs(1));
  EXPECT_FALSE(before.detection.footprints[1].line);
  EXPECT_LT(before.detection.pairs[0].confidence, 0.75 * leaf.confidence);
}

TEST(RibbonDetectorTest, AStepBetweenTwoLevelsIsNotALine) {
  // A narrow light strip between a dark casing and a darker leaf: each edge is a step
  // between two different levels, however close together.
  cv::Mat image = Band(200, 511, 175, 70);
  image.colRange(204, 512).setTo(cv::Scalar(125));
  RibbonDetectorParams seams;
  seams.seam_lines = true;
  const DetectResult result = RibbonDetector(seams).Detect(image, 60.0);
  ASSERT_TRUE(result.ok());
  ASSERT_FALSE(result.detection.footprints.empty());
  for (const Footprint& fp : result.detection.footprints) EXPECT_FALSE(fp.line) << fp.column_px;
}

TEST(RibbonDetectorTest, AThinLineSeenWithRollIsStillALine) {
  // A 3 px seam 20 grey levels darker than the leaf, crossing the outer processed rows
  // (132 and 348) 2 px either side of where it crosses the centre row: a camera rolled by
  // about a degree. The processed rows' mean level smears it over 7 px; at its darkest
  // columns, where four of the five rows cross it, it is still 16 levels under the leaf.
  cv::Mat image = Band(100, 511, 70, 125);
  for (int row = 0; row < image.rows; ++row) {
    const int col = 300 + static_cast<int>(std::lround(2.0 * (row - 240) / 108.0));
    image.row(row).colRange(col, col + 3).setTo(cv::Scalar(105));
  }
  RibbonDetectorParams seams;
  seams.seam_lines = true;
  const DetectResult result = RibbonDetector(seams).Detect(image, 60.0);
  ASSERT_TRUE(result.ok()) << result.message;
  ASSERT_THAT(result.detection.footprints, SizeIs(2));
  EXPECT_FALSE(result.detection.footprints[0].line);
  EXPECT_TRUE(result.detection.footprints[1].line);
  EXPECT_THAT(result.detection.footprints[1].column_px, DoubleNear(301.0, 1.5));
}

TEST(RibbonDetectorTest, ThresholdPassesAtMostTheTopFivePercent) {
  cv::Mat image(480, 512, CV_8UC1);
  cv::RNG rng(9);
  rng.fill(image, cv::RNG::UNIFORM, 0, 256);  // strong texture everywhere
  RibbonDetectorParams params;
  params.row_mode = RowMode::kFullFrame;
  const RibbonDetector detector(params);
  const DetectResult result = detector.Detect(image, 72.0);
  ASSERT_TRUE(result.ok());
  long long passed = 0;
  long long total = 0;
  std::vector<float> out(512);
  for (int row : result.detection.rows) {
    PrewittRow(image.data, 512, image.step[0], row, out.data());
    for (int c = 2; c < 510; ++c) {
      ++total;
      if (std::abs(out[c]) >= result.detection.threshold - 1e-6) ++passed;
    }
  }
  EXPECT_LE(static_cast<double>(passed) / total, 0.05);
  EXPECT_GT(static_cast<double>(passed) / total, 0.04);
}

TEST(RibbonDetectorTest, NoisyBlankFrameGivesNoFootprint) {
  cv::Mat image(480, 512, CV_8UC1);
  cv::RNG rng(4);
  rng.fill(image, cv::RNG::NORMAL, 150, 3);
  const DetectResult result = RibbonDetector().Detect(image, 72.0);
  ASSERT_TRUE(result.ok());
  EXPECT_THAT(result.detection.footprints, IsEmpty());
  EXPECT_THAT(result.detection.pairs, IsEmpty());
}

TEST(RibbonDetectorTest, FullFrameModeUsesEveryInteriorRowAndIgnoresRange) {
  RibbonDetectorParams params;
  params.row_mode = RowMode::kFullFrame;
  const DetectResult result =
      RibbonDetector(params).Detect(Band(200, 259), std::numeric_limits<double>::quiet_NaN());
  ASSERT_TRUE(result.ok()) << result.message;
  EXPECT_THAT(result.detection.rows, SizeIs(476));
  ASSERT_THAT(result.detection.pairs, SizeIs(1));
  EXPECT_EQ(result.detection.footprints[0].rows_hit, 476);
}

TEST(RibbonDetectorTest, RawViewWithPaddedStepGivesTheSameResultAsTheMat) {
  const cv::Mat image = Band(150, 200);
  cv::Mat padded(480, 520, CV_8UC1, cv::Scalar(0));
  image.copyTo(padded.colRange(0, 512));
  ImageView view;
  view.width_px = 512;
  view.height_px = 480;
  view.step_bytes = 520;
  view.encoding = "mono8";
  view.data = padded.data;
  view.size_bytes = 520 * 480;
  const DetectResult a = RibbonDetector().Detect(image, 90.0);
  const DetectResult b = RibbonDetector().Detect(view, 90.0);
  ASSERT_TRUE(b.ok()) << b.message;
  ASSERT_THAT(b.detection.footprints, SizeIs(a.detection.footprints.size()));
  EXPECT_DOUBLE_EQ(b.detection.footprints[0].column_px, a.detection.footprints[0].column_px);
}

// --- Bad input: a clear error result, never a crash. ---

TEST(RibbonDetectorBadInputTest, EmptyMatIsAnEmptyFrameError) {
  const DetectResult result = RibbonDetector().Detect(cv::Mat(), 72.0);
  EXPECT_EQ(result.status, DetectStatus::kEmptyFrame);
  EXPECT_FALSE(result.message.empty());
}

TEST(RibbonDetectorBadInputTest, ColourMatIsAnEncodingError) {
  const cv::Mat colour(480, 512, CV_8UC3, cv::Scalar(1, 2, 3));
  EXPECT_EQ(RibbonDetector().Detect(colour, 72.0).status, DetectStatus::kUnknownEncoding);
}

TEST(RibbonDetectorBadInputTest, ZeroSizedViewIsAnEmptyFrameError) {
  const cv::Mat image = Band(10, 20);
  ImageView view = Mono8View(image);
  view.width_px = 0;
  EXPECT_EQ(RibbonDetector().Detect(view, 72.0).status, DetectStatus::kEmptyFrame);
  view = Mono8View(image);
  view.data = nullptr;
  EXPECT_EQ(RibbonDetector().Detect(view, 72.0).status, DetectStatus::kEmptyFrame);
}

TEST(RibbonDetectorBadInputTest, DataLengthNotMatchingTheSizeIsRejected) {
  const cv::Mat image = Band(10, 20);
  ImageView view = Mono8View(image);
  view.size_bytes -= 1;
  const DetectResult result = RibbonDetector().Detect(view, 72.0);
  EXPECT_EQ(result.status, DetectStatus::kSizeMismatch);
  EXPECT_THAT(result.message, ::testing::HasSubstr("does not match"));
  view = Mono8View(image);
  view.step_bytes = 100;  // below the width
  EXPECT_EQ(RibbonDetector().Detect(view, 72.0).status, DetectStatus::kSizeMismatch);
  view = Mono8View(image);
  view.height_px = 1 << 20;  // absurd header
  EXPECT_EQ(RibbonDetector().Detect(view, 72.0).status, DetectStatus::kSizeMismatch);
}

TEST(RibbonDetectorBadInputTest, UnknownEncodingIsRejected) {
  const cv::Mat image = Band(10, 20);
  ImageView view = Mono8View(image);
  view.encoding = "rgb8";
  EXPECT_EQ(RibbonDetector().Detect(view, 72.0).status, DetectStatus::kUnknownEncoding);
}

TEST(RibbonDetectorBadInputTest, FrameSmallerThanTheFilterIsRejected) {
  const cv::Mat tiny(4, 4, CV_8UC1, cv::Scalar(0));
  EXPECT_EQ(RibbonDetector().Detect(tiny, 72.0).status, DetectStatus::kTooSmall);
}

TEST(RibbonDetectorBadInputTest, NonFiniteOrNegativeRangeIsRejectedInFiveRowMode) {
  const cv::Mat image = Band(10, 20);
  EXPECT_EQ(RibbonDetector().Detect(image, std::numeric_limits<double>::quiet_NaN()).status,
            DetectStatus::kBadRange);
  EXPECT_EQ(RibbonDetector().Detect(image, -5.0).status, DetectStatus::kBadRange);
  EXPECT_EQ(RibbonDetector().Detect(image, std::numeric_limits<double>::infinity()).status,
            DetectStatus::kBadRange);
}

TEST(RibbonDetectorParamsTest, InconsistentParametersThrowAtConstruction) {
  RibbonDetectorParams params;
  params.threshold_fraction = 0.0;
  EXPECT_THROW(RibbonDetector{params}, std::invalid_argument);
  params = {};
  params.clump_min_nonempty = 6;
  EXPECT_THROW(RibbonDetector{params}, std::invalid_argument);
  params = {};
  params.line_side_agreement = -1.0;
  EXPECT_THROW(RibbonDetector{params}, std::invalid_argument);
}

}  // namespace
}  // namespace stickrep::vision
