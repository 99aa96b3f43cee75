#include "localizer/localizer_config.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "common/input_error.h"
#include "common/strict_yaml.h"
#include "localizer/test_ring.h"

namespace stickrep::localizer {
namespace {

namespace fs = std::filesystem;

const fs::path kConfigs = fs::path(STICKREP_SOURCE_DIR) / "configs";

std::string Read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

map::Map Hall() {
  using map::DoorClass;
  using map::Edge;
  return StraightRingMap({Edge::Wall(120), Edge::Door(DoorClass::k36), Edge::Wall(80),
                          Edge::Door(DoorClass::k40)},
                         "hall");
}

TEST(LocalizerConfigTest, ShippedSettingsWeighEdgesByTheModelMeasuredNearestTheirRange) {
  const LocalizerSettings s = LoadLocalizerSettings(
      StrictYaml::LoadFile((kConfigs / "localizer.yaml").string()).Child("localizer"));
  ASSERT_FALSE(s.ranged_error_model_files.empty());
  const LocalizerConfig c = MakeLocalizerConfig(s, Hall());
  // Every model states the range it was measured at, and the ranges differ.
  ASSERT_TRUE(std::isfinite(c.bayes.confusion_range_in));
  ASSERT_EQ(c.bayes.ranged.size(), s.ranged_error_model_files.size());
  for (const auto& r : c.bayes.ranged) {
    EXPECT_GT(std::abs(r.camera_range_in - c.bayes.confusion_range_in), 4.0);
    // Nearer the wall doors are missed more often (docs/whereami.md).
    if (r.camera_range_in < c.bayes.confusion_range_in) {
      EXPECT_GT(r.confusion.missed, c.bayes.confusion.missed);
    }
  }
}

TEST(LocalizerConfigTest, ARangedModelWithoutItsRangeIsRejectedNamingTheFile) {
  const fs::path dir = fs::path(::testing::TempDir()) / "localizer_config_test";
  fs::create_directories(dir);
  for (const char* f : {"localizer.yaml", "study.yaml", "error_model_live.yaml"}) {
    fs::copy_file(kConfigs / f, dir / f, fs::copy_options::overwrite_existing);
  }
  // A model file in the schema, but without camera_range_in (error_model_paper.yaml).
  std::string text = Read(dir / "localizer.yaml");
  const std::string key = "ranged_error_model_files:";
  const std::size_t at = text.find(key);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, text.find('\n', at) - at, key + " [no_range.yaml]");
  std::ofstream(dir / "localizer.yaml") << text;
  fs::copy_file(kConfigs / "error_model_paper.yaml", dir / "no_range.yaml",
                fs::copy_options::overwrite_existing);
  const LocalizerSettings s = LoadLocalizerSettings(
      StrictYaml::LoadFile((dir / "localizer.yaml").string()).Child("localizer"));
  try {
    MakeLocalizerConfig(s, Hall());
    FAIL() << "accepted a ranged model without its range";
  } catch (const InputError& e) {
    EXPECT_NE(e.file().find("no_range.yaml"), std::string::npos) << e.what();
    EXPECT_NE(e.key().find("camera_range_in"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace stickrep::localizer
