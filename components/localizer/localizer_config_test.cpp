// The localizer's settings: which observation model a map gets (ForMap), and the
// `on_marked_maps` block's keys.
#include "localizer/localizer_config.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "common/config_paths.h"
#include "common/input_error.h"
#include "localizer/shipped_settings.h"
#include "localizer/test_ring.h"
#include "stickrep/map_io.h"

namespace stickrep::localizer {
namespace {

using ::testing::HasSubstr;

// The shipped text with `extra` inserted as the first line of the on_marked_maps block.
std::string WithMarkedLine(std::string text, const std::string& extra) {
  const std::string block = "  on_marked_maps:\n";
  const auto at = text.find(block);
  EXPECT_NE(at, std::string::npos);
  if (at == std::string::npos) return text;
  return text.insert(at + block.size(), "    " + extra + "\n");
}

map::Map HallWithDoor(const std::string& pattern) {
  return StraightRingMap({map::Edge::Wall(100), map::Edge::Door(map::DoorClass::k36, pattern),
                          map::Edge::Wall(100), map::Edge::Door(map::DoorClass::k36)},
                         "hall");
}

TEST(LocalizerSettingsTest, OnlyADoorWithASurveyedMarkMakesAMarkedMap) {
  EXPECT_TRUE(HasSurveyedMarks(HallWithDoor("old_window")));
  EXPECT_TRUE(HasSurveyedMarks(HallWithDoor("poster")));
  EXPECT_TRUE(HasSurveyedMarks(HallWithDoor("no_window")));
  // No pattern, or one that does not say what the leaf shows: nothing surveyed.
  EXPECT_FALSE(HasSurveyedMarks(HallWithDoor("")));
  EXPECT_FALSE(HasSurveyedMarks(HallWithDoor("double_leaf")));
}

TEST(LocalizerSettingsTest, AMarkedMapGetsTheMarkedModelAndAnUnmarkedOneTheDefault) {
  const LocalizerSettings shipped = Load(Shipped());
  ASSERT_TRUE(shipped.on_marked_maps.has_value());
  const ObservationSettings& marked = *shipped.on_marked_maps;
  // The two models differ in the keys that must go together.
  ASSERT_NE(marked.error_model_file, shipped.observation.error_model_file);
  ASSERT_NE(marked.bayes_threshold, shipped.observation.bayes_threshold);

  const LocalizerSettings on_marked = ForMap(shipped, HallWithDoor("old_window"));
  EXPECT_EQ(on_marked.observation.error_model_file, marked.error_model_file);
  EXPECT_EQ(on_marked.observation.bayes_threshold, marked.bayes_threshold);
  EXPECT_EQ(on_marked.observation.bayes_lost_threshold, marked.bayes_lost_threshold);
  EXPECT_EQ(on_marked.observation.bayes_false_door_fit, marked.bayes_false_door_fit);
  EXPECT_EQ(on_marked.observation.bayes_max_missed_doors, marked.bayes_max_missed_doors);
  EXPECT_EQ(on_marked.observation.calibration.slope, marked.calibration.slope);
  EXPECT_EQ(on_marked.observation.calibration.offset, marked.calibration.offset);
  EXPECT_FALSE(on_marked.on_marked_maps.has_value());
  EXPECT_TRUE(on_marked.observation_for_marked_map);

  const LocalizerSettings on_plain = ForMap(shipped, HallWithDoor(""));
  EXPECT_EQ(on_plain.observation.error_model_file, shipped.observation.error_model_file);
  EXPECT_EQ(on_plain.observation.bayes_threshold, shipped.observation.bayes_threshold);
  EXPECT_EQ(on_plain.observation.bayes_false_door_fit, shipped.observation.bayes_false_door_fit);
  EXPECT_FALSE(on_plain.observation_for_marked_map);

  // The model the settings name is the one the Bayes matcher gets.
  const LocalizerConfig config = MakeLocalizerConfig(on_marked, HallWithDoor("old_window"));
  EXPECT_EQ(config.bayes.settings.threshold, marked.bayes_threshold);
  EXPECT_EQ(config.bayes.settings.false_door_fit, marked.bayes_false_door_fit);
  EXPECT_EQ(config.bayes.settings.max_missed_doors, marked.bayes_max_missed_doors);
  EXPECT_EQ(config.lost_threshold, marked.bayes_lost_threshold);
}

TEST(LocalizerSettingsTest, TheShippedFloorsGetTheModelTheirSurveySupports) {
  const std::string maps = DataDir() + "/maps/";
  EXPECT_TRUE(HasSurveyedMarks(map::LoadMap(maps + "engineering_building_3f.yaml")));
  EXPECT_FALSE(HasSurveyedMarks(map::LoadMap(maps + "teaching_building_1f.yaml")));
  EXPECT_FALSE(HasSurveyedMarks(map::LoadMap(maps + "science_hall_2f.yaml")));
}

TEST(LocalizerSettingsTest, WithoutTheBlockEveryMapGetsTheDefault) {
  std::string text = Shipped();
  const auto at = text.find("  on_marked_maps:\n");
  ASSERT_NE(at, std::string::npos);
  auto end = text.find("\n  ", at + 1);
  while (end != std::string::npos && text.compare(end, 5, "\n    ") == 0) {
    end = text.find("\n  ", end + 1);
  }
  text.erase(at, end + 1 - at);
  const LocalizerSettings s = Load(text);
  EXPECT_FALSE(s.on_marked_maps.has_value());
  const LocalizerSettings on_marked = ForMap(s, HallWithDoor("old_window"));
  EXPECT_EQ(on_marked.observation.error_model_file, s.observation.error_model_file);
  EXPECT_FALSE(on_marked.observation_for_marked_map);
}

TEST(LocalizerSettingsTest, AnUnknownKeyInTheMarkedBlockIsRefusedWithItsPath) {
  try {
    Load(WithMarkedLine(Shipped(), "bayes_outlier: 0.01"));
    FAIL() << "accepted a key the marked model does not take";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("localizer.yaml:"));
    EXPECT_THAT(e.what(), HasSubstr("on_marked_maps"));
    EXPECT_THAT(e.what(), HasSubstr("bayes_outlier"));
  }
}

TEST(LocalizerSettingsTest, AMarkedBarTheFilterCannotReachIsRefusedWithItsKey) {
  std::string text = Shipped();
  const auto block = text.find("  on_marked_maps:\n");
  ASSERT_NE(block, std::string::npos);
  const std::string key = "    localized_confidence: ";
  const auto at = text.find(key, block);
  ASSERT_NE(at, std::string::npos);
  const auto from = at + key.size();
  text.replace(from, text.find('\n', from) - from, "0.99999");
  try {
    Load(text);
    FAIL() << "accepted a bar that needs a posterior over 0.999999";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("on_marked_maps"));
    EXPECT_THAT(e.what(), HasSubstr("localized_confidence"));
  }
}

}  // namespace
}  // namespace stickrep::localizer
