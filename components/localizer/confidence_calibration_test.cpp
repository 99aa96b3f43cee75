#include "localizer/confidence_calibration.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/input_error.h"
#include "localizer/localizer_config.h"
#include "localizer/shipped_settings.h"

namespace stickrep::localizer {
namespace {

using ::testing::HasSubstr;

TEST(ConfidenceCalibrationTest, IdentityLeavesThePosteriorAsItIs) {
  const ConfidenceCalibration identity;
  for (double p : {0.0, 0.2, 0.5, 0.995, 1.0}) {
    EXPECT_DOUBLE_EQ(identity.Calibrated(p), p);
    EXPECT_DOUBLE_EQ(identity.PosteriorFor(p), p);
  }
}

// The fit of docs/whereami.md over 1000 runs: the bins' mean posteriors and what the fit
// gives there (the measured shares right were 0.9946 and 0.9774).
TEST(ConfidenceCalibrationTest, AnOverConfidentPosteriorIsPulledDown) {
  const ConfidenceCalibration c{0.765, -0.984};
  EXPECT_NEAR(c.Calibrated(0.9998), 0.9961, 5e-4);
  EXPECT_NEAR(c.Calibrated(0.9972), 0.9710, 5e-4);
  EXPECT_LT(c.Calibrated(0.5), 0.5);
  // Monotonic, and never outside [0, 1] at the filter's floor and ceiling.
  double last = 0.0;
  for (double p = 0.0; p <= 1.0; p += 0.01) {
    const double q = c.Calibrated(p);
    EXPECT_GE(q, last);
    EXPECT_GE(q, 0.0);
    EXPECT_LE(q, 1.0);
    last = q;
  }
}

TEST(ConfidenceCalibrationTest, PosteriorForInvertsTheCalibration) {
  const ConfidenceCalibration c{0.765, -0.984};
  for (double q : {0.05, 0.5, 0.9, 0.99, 0.995, 0.999}) {
    EXPECT_NEAR(c.Calibrated(c.PosteriorFor(q)), q, 1e-12);
  }
  // 99.5 % right needs a posterior of 0.99973 (docs/whereami.md).
  EXPECT_NEAR(c.PosteriorFor(0.995), 0.99973, 1e-5);
}

// The shipped text with `key`'s value (the rest of its line) replaced by `value`.
std::string WithValue(std::string text, const std::string& key, const std::string& value) {
  const auto at = text.find(key + ": ");
  EXPECT_NE(at, std::string::npos) << key;
  if (at == std::string::npos) return text;
  const auto from = at + key.size() + 2;
  return text.replace(from, text.find('\n', from) - from, value);
}

TEST(ConfidenceCalibrationTest, TheShippedThresholdIsACalibratedConfidence) {
  const LocalizerSettings shipped = Load(Shipped());
  ASSERT_TRUE(shipped.on_marked_maps.has_value());
  std::vector<ObservationSettings> models = {shipped.observation, *shipped.on_marked_maps};
  for (const auto& [name, own] : shipped.on_maps) models.push_back(own);
  EXPECT_GE(models.size(), 3U);  // the science hall's own
  for (const ObservationSettings& s : models) {
    EXPECT_GT(s.calibration.slope, 0.0);
    // The filter's own threshold is the posterior whose calibrated confidence is the one
    // declared: never below it for an over-confident filter.
    EXPECT_NEAR(s.calibration.Calibrated(s.bayes_threshold), s.localized_confidence, 1e-9);
    EXPECT_GE(s.bayes_threshold, s.localized_confidence);
  }
}

TEST(ConfidenceCalibrationTest, AConfidenceTheFilterCannotReachIsRefusedWithItsKey) {
  const std::string text = WithValue(Shipped(), "localized_confidence", "0.99999");
  try {
    Load(text);
    FAIL() << "accepted a confidence that needs a posterior over 0.999999";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("localizer.yaml:"));
    EXPECT_THAT(e.what(), HasSubstr("localized_confidence"));
  }
}

TEST(ConfidenceCalibrationTest, ASlopeOfZeroIsRefused) {
  EXPECT_THROW(Load(WithValue(Shipped(), "confidence_calibration_slope", "0")), InputError);
}

}  // namespace
}  // namespace stickrep::localizer
