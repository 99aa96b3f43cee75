// The localizer's settings: which observation model a map gets (ForMap), and the
// `on_marked_maps`, `on_narrow_maps` and `on_maps` blocks' keys.
#include "localizer/localizer_config.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

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

// Where the on_marked_maps block of `text` begins and ends (the offset past its last line);
// begin is npos when there is none.
std::pair<std::size_t, std::size_t> MarkedBlock(const std::string& text) {
  const auto begin = text.find("  on_marked_maps:\n");
  if (begin == std::string::npos) return {begin, begin};
  auto end = text.find("\n  ", begin + 1);
  while (end != std::string::npos && text.compare(end, 5, "\n    ") == 0) {
    end = text.find("\n  ", end + 1);
  }
  return {begin, end == std::string::npos ? text.size() : end + 1};
}

// The shipped text with an on_narrow_maps block after the on_marked_maps block: the model
// measured in narrow hallways (configs/error_model_narrow.yaml), the default calibration.
std::string WithNarrowBlock(std::string text) {
  const auto [begin, end] = MarkedBlock(text);
  EXPECT_NE(begin, std::string::npos);
  if (begin == std::string::npos) return text;
  return text.insert(end,
                     "  on_narrow_maps:\n"
                     "    max_hallway_width_in: 100\n"
                     "    error_model_file: error_model_narrow.yaml\n"
                     "    confidence_calibration_slope: 0.765\n"
                     "    confidence_calibration_offset: -0.984\n"
                     "    localized_confidence: 0.955\n"
                     "    bayes_lost_threshold: 0.001\n"
                     "    bayes_false_door_fit: false\n"
                     "    bayes_max_missed_doors: 2\n");
}

// The shipped text with a block for the map `name` in its on_maps block (after the
// on_marked_maps block when there is none): the default model with the calibration `slope`,
// offset -1.5 (`extra`: one more line in that map's block).
std::string WithOwnMapBlock(std::string text, const std::string& name, const std::string& slope,
                            const std::string& extra = "") {
  const std::string maps = "  on_maps:\n";
  std::size_t at = text.find(maps);
  if (at == std::string::npos) {
    at = MarkedBlock(text).second;
    EXPECT_NE(at, std::string::npos);
    if (at == std::string::npos) return text;
    text.insert(at, maps);
  }
  const std::string block =
      "    " + name + ":\n      error_model_file: error_model_live.yaml\n" +
      "      confidence_calibration_slope: " + slope + "\n" +
      "      confidence_calibration_offset: -1.5\n" + "      localized_confidence: 0.955\n" +
      "      bayes_lost_threshold: 0.001\n" + "      bayes_false_door_fit: false\n" +
      "      bayes_max_missed_doors: 2\n" + extra;
  return text.insert(at + maps.size(), block);
}

// `text` with the value of the first line `key` ("  bayes_lost_confirm_edges: ") at or after
// offset `from` set to `value`.
std::string WithValue(std::string text, const std::string& key, const std::string& value,
                      std::size_t from = 0) {
  const auto at = text.find(key, from);
  EXPECT_NE(at, std::string::npos) << key;
  if (at == std::string::npos) return text;
  const auto begin = at + key.size();
  return text.replace(begin, text.find('\n', begin) - begin, value);
}

// Loading `text` fails with an InputError that names the file's line and each of `words`.
void ExpectRefused(const std::string& text, const std::vector<std::string>& words) {
  try {
    Load(text);
    ADD_FAILURE() << "accepted: " << words.back();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("localizer.yaml:"));
    for (const std::string& w : words) EXPECT_THAT(e.what(), HasSubstr(w));
  }
}

map::Map HallWithDoor(const std::string& pattern, std::optional<double> width_in = std::nullopt) {
  return StraightRingMap({map::Edge::Wall(100), map::Edge::Door(map::DoorClass::k36, pattern),
                          map::Edge::Wall(100), map::Edge::Door(map::DoorClass::k36)},
                         "hall", width_in);
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
  EXPECT_EQ(on_marked.observation_for, ObservationFor::kMarkedMap);

  const LocalizerSettings on_plain = ForMap(shipped, HallWithDoor(""));
  EXPECT_EQ(on_plain.observation.error_model_file, shipped.observation.error_model_file);
  EXPECT_EQ(on_plain.observation.bayes_threshold, shipped.observation.bayes_threshold);
  EXPECT_EQ(on_plain.observation.bayes_false_door_fit, shipped.observation.bayes_false_door_fit);
  EXPECT_EQ(on_plain.observation_for, ObservationFor::kDefault);

  // The model the settings name is the one the Bayes matcher gets.
  const LocalizerConfig config = MakeLocalizerConfig(on_marked, HallWithDoor("old_window"));
  EXPECT_EQ(config.bayes.settings.threshold, marked.bayes_threshold);
  EXPECT_EQ(config.bayes.settings.false_door_fit, marked.bayes_false_door_fit);
  EXPECT_EQ(config.bayes.settings.max_missed_doors, marked.bayes_max_missed_doors);
  EXPECT_EQ(config.lost_threshold, marked.bayes_lost_threshold);
}

// The shipped settings with `key: true` among a marked map's keys (where it is not already).
LocalizerSettings ShippedWithMarkedKey(const std::string& key) {
  std::string text = Shipped();
  const std::string marked_last = "    bayes_max_missed_doors: 4\n";
  const std::size_t at = text.find(marked_last);
  EXPECT_NE(at, std::string::npos);
  const std::string line = "    " + key + ": true\n";
  if (at != std::string::npos && text.find(line) == std::string::npos) {
    text.insert(at + marked_last.size(), line);
  }
  return Load(text);
}

TEST(LocalizerSettingsTest, TheRestOfAWallPastAFalseDoorRunsOnOnlyWhereTheSettingsSaySo) {
  // The study's settings turn it on; a model whose keys do not is weighed without it.
  const LocalizerSettings settings = ShippedWithMarkedKey("bayes_w2_over_missed_doors");
  ASSERT_TRUE(settings.on_marked_maps.has_value());
  EXPECT_TRUE(settings.on_marked_maps->bayes_w2_over_missed_doors);
  EXPECT_FALSE(settings.observation.bayes_w2_over_missed_doors);
  const map::Map marked = HallWithDoor("old_window"), plain = HallWithDoor("");
  EXPECT_TRUE(
      MakeLocalizerConfig(ForMap(settings, marked), marked).bayes.settings.w2_over_missed_doors);
  EXPECT_FALSE(
      MakeLocalizerConfig(ForMap(settings, plain), plain).bayes.settings.w2_over_missed_doors);
}

TEST(LocalizerSettingsTest, TheTravelDirectionIsTakenFromTheOdometerOnlyWhereTheSettingsSaySo) {
  const LocalizerSettings settings = ShippedWithMarkedKey("bayes_direction_from_travel");
  ASSERT_TRUE(settings.on_marked_maps.has_value());
  EXPECT_TRUE(settings.on_marked_maps->bayes_direction_from_travel);
  const map::Map marked = HallWithDoor("old_window"), plain = HallWithDoor("");
  EXPECT_TRUE(MakeLocalizerConfig(ForMap(settings, marked), marked).direction_from_travel);
  EXPECT_EQ(MakeLocalizerConfig(ForMap(settings, plain), plain).direction_from_travel,
            settings.observation.bayes_direction_from_travel);
  // Absent, it is off.
  EXPECT_FALSE(ObservationSettings{}.bayes_direction_from_travel);
}

TEST(LocalizerSettingsTest, AShortFirstPartPastMissedDoorsIsWeighedOnlyWhereTheSettingsSaySo) {
  const LocalizerSettings settings = ShippedWithMarkedKey("bayes_first_part_in_noise");
  ASSERT_TRUE(settings.on_marked_maps.has_value());
  EXPECT_TRUE(settings.on_marked_maps->bayes_first_part_in_noise);
  EXPECT_FALSE(settings.observation.bayes_first_part_in_noise);
  const map::Map marked = HallWithDoor("old_window"), plain = HallWithDoor("");
  EXPECT_TRUE(
      MakeLocalizerConfig(ForMap(settings, marked), marked).bayes.settings.first_part_in_noise);
  EXPECT_FALSE(
      MakeLocalizerConfig(ForMap(settings, plain), plain).bayes.settings.first_part_in_noise);
}

TEST(LocalizerSettingsTest, TheShippedFloorsGetTheModelTheirSurveySupports) {
  const std::string maps = DataDir() + "/maps/";
  const map::Map engineering = map::LoadMap(maps + "engineering_building_3f.yaml");
  const map::Map teaching = map::LoadMap(maps + "teaching_building_1f.yaml");
  const map::Map science = map::LoadMap(maps + "science_hall_2f.yaml");
  EXPECT_TRUE(HasSurveyedMarks(engineering));
  EXPECT_FALSE(HasSurveyedMarks(teaching));
  EXPECT_FALSE(HasSurveyedMarks(science));
  // The Engineering Building's rings give no width (the text's 120 in hallways); the
  // teaching building's corridors are 96 and 88 in, the science hall's 88.
  EXPECT_EQ(MapHallwayWidthIn(engineering, 120.0), 120.0);
  EXPECT_EQ(MapHallwayWidthIn(teaching, 120.0), 96.0);
  EXPECT_EQ(MapHallwayWidthIn(science, 120.0), 88.0);

  // As shipped, no model for narrow hallways: the teaching building and the science hall
  // each get their own calibration of the default model at the same stated risk, both fitted
  // with the direction of travel.
  const LocalizerSettings shipped = Load(Shipped());
  EXPECT_FALSE(shipped.on_narrow_maps.has_value());
  EXPECT_EQ(ForMap(shipped, engineering).observation_for, ObservationFor::kMarkedMap);
  for (const map::Map* floor : {&teaching, &science}) {
    const LocalizerSettings own = ForMap(shipped, *floor);
    EXPECT_EQ(own.observation_for, ObservationFor::kOwnMap) << floor->info().name;
    EXPECT_EQ(own.observation.error_model_file, shipped.observation.error_model_file);
    EXPECT_EQ(own.observation.localized_confidence, shipped.observation.localized_confidence);
    EXPECT_GT(own.observation.bayes_threshold, shipped.observation.bayes_threshold);
    EXPECT_TRUE(own.observation.bayes_direction_from_travel) << floor->info().name;
  }
  // An unseen floor takes the direction too: the default calibration was fitted with it, on
  // three floors together, and its bar is nearer the floors' own than the Engineering
  // Building's alone was (the posterior 0.9949).
  EXPECT_TRUE(shipped.observation.bayes_direction_from_travel);
  EXPECT_GT(shipped.observation.bayes_threshold, 0.999);
  // With one, the floors with settings of their own and the marked floor keep theirs, and a
  // floor of the text's 120 in hallways gets the default.
  const LocalizerSettings narrow = Load(WithNarrowBlock(Shipped()));
  EXPECT_EQ(ForMap(narrow, engineering).observation_for, ObservationFor::kMarkedMap);
  EXPECT_EQ(ForMap(narrow, teaching).observation_for, ObservationFor::kOwnMap);
  EXPECT_EQ(ForMap(narrow, science).observation_for, ObservationFor::kOwnMap);
  EXPECT_EQ(ForMap(narrow, map::LoadMap(maps + "storefront.yaml")).observation_for,
            ObservationFor::kDefault);
}

TEST(LocalizerSettingsTest, ANarrowMapGetsTheNarrowModelUnlessItsDoorsAreMarked) {
  const LocalizerSettings shipped = Load(WithNarrowBlock(Shipped()));
  ASSERT_TRUE(shipped.on_narrow_maps.has_value());
  const NarrowMapSettings& narrow = *shipped.on_narrow_maps;
  ASSERT_NE(narrow.observation.error_model_file, shipped.observation.error_model_file);
  const double at_most = narrow.max_hallway_width_in;

  const LocalizerSettings on_narrow = ForMap(shipped, HallWithDoor("", at_most));
  EXPECT_EQ(on_narrow.observation_for, ObservationFor::kNarrowMap);
  EXPECT_EQ(on_narrow.observation.error_model_file, narrow.observation.error_model_file);
  EXPECT_EQ(on_narrow.observation.bayes_threshold, narrow.observation.bayes_threshold);
  EXPECT_EQ(on_narrow.observation.calibration.slope, narrow.observation.calibration.slope);
  EXPECT_FALSE(on_narrow.on_narrow_maps.has_value());

  // An inch wider, or no width given (the default hallway's), is not narrow.
  EXPECT_EQ(ForMap(shipped, HallWithDoor("", at_most + 1.0)).observation_for,
            ObservationFor::kDefault);
  EXPECT_EQ(ForMap(shipped, HallWithDoor("")).observation_for, ObservationFor::kDefault);
  // Surveyed marks decide first: their model was measured and calibrated with them.
  EXPECT_EQ(ForMap(shipped, HallWithDoor("old_window", at_most)).observation_for,
            ObservationFor::kMarkedMap);
}

TEST(LocalizerSettingsTest, TheNarrowBlockNeedsItsWidthAndRefusesUnknownKeys) {
  const std::string text = WithNarrowBlock(Shipped());
  const std::string key = "    max_hallway_width_in: ";
  const auto at = text.find(key);
  ASSERT_NE(at, std::string::npos);
  const auto line_end = text.find('\n', at);
  // The width left out, or a key the block does not take added after it.
  std::string without = text;
  without.replace(at, line_end - at, "    # no width");
  std::string with_unknown = text;
  with_unknown.insert(line_end + 1, "    bayes_outlier: 0.01\n");
  for (const auto& [edited, named] :
       {std::pair{without, "max_hallway_width_in"}, std::pair{with_unknown, "bayes_outlier"}}) {
    try {
      Load(edited);
      FAIL() << "accepted the narrow block without a check on " << named;
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr("localizer.yaml:"));
      EXPECT_THAT(e.what(), HasSubstr("on_narrow_maps"));
      EXPECT_THAT(e.what(), HasSubstr(named));
    }
  }
}

TEST(LocalizerSettingsTest, WithoutTheBlockEveryMapGetsTheDefault) {
  std::string text = Shipped();
  const auto [begin, end] = MarkedBlock(text);
  ASSERT_NE(begin, std::string::npos);
  text.erase(begin, end - begin);
  const LocalizerSettings s = Load(text);
  EXPECT_FALSE(s.on_marked_maps.has_value());
  const LocalizerSettings on_marked = ForMap(s, HallWithDoor("old_window"));
  EXPECT_EQ(on_marked.observation.error_model_file, s.observation.error_model_file);
  EXPECT_EQ(on_marked.observation_for, ObservationFor::kDefault);
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
  const std::string text = Shipped();
  const auto block = text.find("  on_marked_maps:\n");
  ASSERT_NE(block, std::string::npos);
  // A bar that needs a posterior over 0.999999.
  ExpectRefused(WithValue(text, "    localized_confidence: ", "0.99999", block),
                {"on_marked_maps", "localized_confidence"});
}

TEST(LocalizerSettingsTest, TheEdgesThatConfirmALossReachTheLocalizerAndAreBounded) {
  const std::string key = "  bayes_lost_confirm_edges: ";
  const std::string text = Shipped();
  const LocalizerSettings shipped = Load(text);
  const map::Map m = HallWithDoor("");
  EXPECT_EQ(MakeLocalizerConfig(ForMap(shipped, m), m).lost_confirm_edges,
            shipped.bayes_lost_confirm_edges);
  EXPECT_EQ(MakeLocalizerConfig(ForMap(Load(WithValue(text, key, "3")), m), m).lost_confirm_edges,
            3);
  ExpectRefused(WithValue(text, key, "11"), {"bayes_lost_confirm_edges"});
}

TEST(LocalizerSettingsTest, WhetherTheSilenceTestsAHeldPoseReachesTheLocalizer) {
  const std::string key = "  bayes_silence_tests_pose: ";
  const std::string text = Shipped();
  const map::Map m = HallWithDoor("");
  for (const bool on : {true, false}) {
    const std::string value = on ? "true" : "false";
    EXPECT_EQ(
        MakeLocalizerConfig(ForMap(Load(WithValue(text, key, value)), m), m).silence_tests_pose,
        on);
  }
  ExpectRefused(WithValue(text, key, "often"), {"bayes_silence_tests_pose"});
}

TEST(LocalizerSettingsTest, WhetherTheBestPlaceHoldsItsNeighboursReachesTheFilter) {
  const std::string key = "  bayes_best_with_neighbours: ";
  const std::string text = Shipped();
  const map::Map m = HallWithDoor("");
  for (const bool on : {true, false}) {
    const std::string value = on ? "true" : "false";
    EXPECT_EQ(MakeLocalizerConfig(ForMap(Load(WithValue(text, key, value)), m), m)
                  .bayes.settings.best_with_neighbours,
              on);
  }
  ExpectRefused(WithValue(text, key, "mostly"), {"bayes_best_with_neighbours"});
}

TEST(LocalizerSettingsTest, AFloorNamedInOnMapsGetsItsOwnCalibrationBeforeAnyOtherModel) {
  // HallWithDoor's map is named "hall".
  const LocalizerSettings s = Load(WithNarrowBlock(WithOwnMapBlock(Shipped(), "hall", "0.5")));
  ASSERT_EQ(s.on_maps.count("hall"), 1U);
  const ObservationSettings& own = s.on_maps.at("hall");
  EXPECT_EQ(own.calibration.slope, 0.5);
  EXPECT_EQ(own.calibration.offset, -1.5);
  // The bar is the same stated risk; under the floor's calibration it needs another
  // posterior than the default's.
  EXPECT_NE(own.bayes_threshold, s.observation.bayes_threshold);
  EXPECT_NEAR(own.calibration.Calibrated(own.bayes_threshold), 0.955, 1e-9);

  // Named, the floor gets its own whether its doors are marked or its hallways narrow.
  for (const map::Map& m : {HallWithDoor(""), HallWithDoor("old_window"),
                            HallWithDoor("", s.on_narrow_maps->max_hallway_width_in)}) {
    const LocalizerSettings on = ForMap(s, m);
    EXPECT_EQ(on.observation_for, ObservationFor::kOwnMap);
    EXPECT_EQ(on.observation.calibration.slope, own.calibration.slope);
    EXPECT_EQ(on.observation.bayes_threshold, own.bayes_threshold);
    EXPECT_TRUE(on.on_maps.empty());
  }
  EXPECT_STREQ(ObservationForName(ObservationFor::kOwnMap), "the map's own, measured on it");

  // Another floor's block leaves this one to the rules before.
  const LocalizerSettings other = Load(WithOwnMapBlock(Shipped(), "another_floor", "0.5"));
  EXPECT_EQ(ForMap(other, HallWithDoor("")).observation_for, ObservationFor::kDefault);
  EXPECT_EQ(ForMap(other, HallWithDoor("old_window")).observation_for, ObservationFor::kMarkedMap);
}

TEST(LocalizerSettingsTest, AFloorsBlockRefusesAnUnknownKeyAndABadCalibrationWithItsPath) {
  for (const auto& [text, named] :
       {std::pair{WithOwnMapBlock(Shipped(), "hall", "0.5", "      bayes_outlier: 0.01\n"),
                  "bayes_outlier"},
        std::pair{WithOwnMapBlock(Shipped(), "hall", "-1"), "confidence_calibration_slope"}}) {
    try {
      Load(text);
      FAIL() << "accepted the floor's block with a bad " << named;
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr("localizer.yaml:"));
      EXPECT_THAT(e.what(), HasSubstr("on_maps.hall"));
      EXPECT_THAT(e.what(), HasSubstr(named));
    }
  }
}

}  // namespace
}  // namespace stickrep::localizer
