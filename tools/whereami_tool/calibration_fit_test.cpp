// Batches of different floors pooled into one calibration.
#include "whereami_tool/calibration_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "common/input_error.h"

namespace stickrep::whereami {
namespace {

// Samples whose rightness follows logit(right) = a logit(c) + b, seeded.
std::vector<ConfidenceSample> Drawn(double a, double b, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> logit(-4.0, 8.0), u(0.0, 1.0);
  std::vector<ConfidenceSample> samples;
  for (int i = 0; i < n; ++i) {
    const double x = logit(rng);
    ConfidenceSample s;
    s.confidence = 1.0 / (1.0 + std::exp(-x));
    s.correct = u(rng) < 1.0 / (1.0 + std::exp(-(a * x + b)));
    samples.push_back(s);
  }
  return samples;
}

// A batch file as stickrep-whereami --json writes it: its samples over `runs` runs.
std::string WriteBatch(const std::string& name, const std::string& map,
                       const std::vector<ConfidenceSample>& samples, int runs, double slope,
                       double offset, double bar) {
  nlohmann::json run_list = nlohmann::json::array();
  for (int r = 0; r < runs; ++r) run_list.push_back({{"seed", r}, {"confidences", {}}});
  for (std::size_t i = 0; i < samples.size(); ++i) {
    run_list[i % runs]["confidences"].push_back({{"confidence", samples[i].confidence},
                                                 {"correct", samples[i].correct},
                                                 {"localized", false}});
  }
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << nlohmann::json{
      {"map", map},
      {"calibration", {{"slope", slope}, {"offset", offset}, {"localized_confidence", bar}}},
      {"runs", run_list}}.dump();
  return path;
}

TEST(CalibrationFitTest, ComposingTheFitMakesItTheIdentity) {
  localizer::ConfidenceCalibration ran_under{0.765, -0.984};
  Reliability::Fit fit;
  fit.slope = 0.8;
  fit.offset = -0.3;
  const localizer::ConfidenceCalibration c = ComposeCalibration(ran_under, fit);
  // For any posterior, the composed confidence is the fit of the published one.
  for (const double p : {0.2, 0.9, 0.999, 0.999999}) {
    const double published = ran_under.Calibrated(p);
    const double x = std::log(published / (1.0 - published));
    const double fitted = 1.0 / (1.0 + std::exp(-(fit.slope * x + fit.offset)));
    EXPECT_NEAR(c.Calibrated(p), fitted, 1e-12) << p;
  }
}

TEST(CalibrationFitTest, PoolsEveryBatchsSamplesIntoOneFit) {
  // Two floors: one over-confident, one nearly calibrated; the pool is their union's fit.
  const std::vector<ConfidenceSample> a = Drawn(0.5, -0.5, 3000, 7), b = Drawn(1.0, 0.0, 1000, 8);
  const std::string fa = WriteBatch("fit_a.json", "floor_a", a, 40, 0.7, -0.9, 0.955);
  const std::string fb = WriteBatch("fit_b.json", "floor_b", b, 30, 0.7, -0.9, 0.955);
  const PooledCalibrationFit f = FitCalibrationFromBatches({fa, fb});
  ASSERT_EQ(f.batches.size(), 2u);
  EXPECT_EQ(f.batches[0].map, "floor_a");
  EXPECT_EQ(f.batches[0].runs, 40);
  EXPECT_EQ(f.batches[1].samples, 1000);
  EXPECT_NEAR(f.batches[0].fit.slope, 0.5, 0.06);
  EXPECT_NEAR(f.batches[1].fit.slope, 1.0, 0.15);
  std::vector<ConfidenceSample> both = a;
  both.insert(both.end(), b.begin(), b.end());
  const Reliability::Fit expected = FitPlatt(both);
  EXPECT_EQ(f.fit.n, 4000);
  // The same samples in another order (the file holds them run by run).
  EXPECT_NEAR(f.fit.slope, expected.slope, 1e-9);
  EXPECT_NEAR(f.fit.offset, expected.offset, 1e-9);
  // Between the two floors' slopes, nearer the floor with more samples.
  EXPECT_GT(f.fit.slope, f.batches[0].fit.slope);
  EXPECT_LT(f.fit.slope, 0.75);
  EXPECT_NEAR(f.composed.slope, expected.slope * 0.7, 1e-9);
  EXPECT_NEAR(f.composed.offset, expected.slope * -0.9 + expected.offset, 1e-9);
  EXPECT_DOUBLE_EQ(f.localized_confidence, 0.955);
}

TEST(CalibrationFitTest, BatchesUnderAnotherCalibrationAreRefused) {
  const std::vector<ConfidenceSample> a = Drawn(0.5, -0.5, 200, 9);
  const std::string fa = WriteBatch("cal_a.json", "floor_a", a, 10, 0.7, -0.9, 0.955);
  const std::string fb = WriteBatch("cal_b.json", "floor_b", a, 10, 0.6, -0.9, 0.955);
  const std::string fc = WriteBatch("cal_c.json", "floor_c", a, 10, 0.7, -0.9, 0.995);
  for (const std::string& other : {fb, fc}) {
    try {
      FitCalibrationFromBatches({fa, other});
      ADD_FAILURE() << other << " was pooled";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), other);
      EXPECT_EQ(e.key(), "calibration");
    }
  }
}

TEST(CalibrationFitTest, AFileWithoutSamplesNamesTheKey) {
  const std::string path = ::testing::TempDir() + "no_samples.json";
  std::ofstream(path) << R"({"map": "m", "calibration": {"slope": 1, "offset": 0,
      "localized_confidence": 0.955}, "runs": [{"seed": 1}]})";
  try {
    FitCalibrationFromBatches({path});
    ADD_FAILURE() << "pooled a batch without samples";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "runs[0].confidences");
  }
  // A sample of the wrong type is refused by key, not thrown as the JSON library's error.
  for (const char* sample :
       {R"({"confidence": 1.5, "correct": true})", R"({"confidence": 0.5, "correct": 1})",
        R"({"confidence": 0.5, "correct": true, "localized": "yes"})", R"([0.5, true])"}) {
    const std::string wrong = ::testing::TempDir() + "wrong_sample.json";
    std::ofstream(wrong) << R"({"map": "m", "calibration": {"slope": 1, "offset": 0,
        "localized_confidence": 0.955}, "runs": [{"confidences": [)"
                         << sample << "]}]}";
    try {
      FitCalibrationFromBatches({wrong});
      ADD_FAILURE() << "pooled " << sample;
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), "runs[0].confidences") << sample;
    }
  }
  const std::string bad = ::testing::TempDir() + "not_json.json";
  std::ofstream(bad) << "{ not json";
  EXPECT_THROW(FitCalibrationFromBatches({bad}), InputError);
  EXPECT_THROW(FitCalibrationFromBatches({::testing::TempDir() + "absent.json"}), InputError);
  EXPECT_THROW(FitCalibrationFromBatches({}), InputError);
}

}  // namespace
}  // namespace stickrep::whereami
