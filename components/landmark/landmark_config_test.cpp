#include "landmark/landmark_config.h"

#include <gtest/gtest.h>

#include <string>

#include "common/config_paths.h"
#include "common/input_error.h"

namespace stickrep::landmark {
namespace {

constexpr const char* kSection = R"(landmark:
  geometry: short_side
  short_side_edges: field_of_view
  min_confidence: 0.25
  row_mode: five_rows
  seam_lines: true
  max_scan_age_s: 0.3
)";

TEST(LandmarkConfigTest, TheShippedFileReadsSeamsAsSteps) {
  const LandmarkConfig config = LoadLandmarkConfig(
      StrictYaml::LoadFile(DefaultConfigDir() + "/landmark.yaml").Child("landmark"));
  EXPECT_FALSE(config.detector.seam_lines);
  EXPECT_EQ(config.detector.row_mode, vision::RowMode::kFiveRows);
}

TEST(LandmarkConfigTest, SeamLinesCanBeSwitchedOn) {
  const LandmarkConfig config =
      LoadLandmarkConfig(StrictYaml::LoadString(kSection, "landmark.yaml").Child("landmark"));
  EXPECT_TRUE(config.detector.seam_lines);
  EXPECT_DOUBLE_EQ(config.estimator.min_confidence, 0.25);
}

TEST(LandmarkConfigTest, AMissingOrBadSeamLinesKeyNamesItsLineAndKey) {
  std::string missing = kSection;
  missing.erase(missing.find("  seam_lines"), std::string("  seam_lines: true\n").size());
  try {
    LoadLandmarkConfig(StrictYaml::LoadString(missing, "landmark.yaml").Child("landmark"));
    FAIL() << "a missing seam_lines was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "landmark.yaml");
    EXPECT_NE(e.key().find("seam_lines"), std::string::npos) << e.what();
  }
  std::string bad = kSection;
  bad.replace(bad.find("seam_lines: true"), 16, "seam_lines: maybe");
  try {
    LoadLandmarkConfig(StrictYaml::LoadString(bad, "landmark.yaml").Child("landmark"));
    FAIL() << "seam_lines: maybe was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 6) << e.what();
    EXPECT_NE(e.key().find("seam_lines"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace stickrep::landmark
