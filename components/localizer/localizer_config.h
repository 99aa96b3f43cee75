#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "common/strict_yaml.h"
#include "localizer/localizer.h"
#include "stickrep/hallway_view.h"
#include "stickrep/map.h"

namespace stickrep::localizer {

// The settings that go with one observation model: the error model, the calibration fitted
// on runs under it, the bar a pose must reach and the LOST threshold chosen under that
// calibration. They are chosen together; one changed alone breaks the others' meaning.
struct ObservationSettings {
  std::string error_model_file;  // resolved against the settings file
  // The Bayes filter's posterior as the published confidence, and the calibrated confidence
  // a pose needs to be declared LOCALIZED (1 - it: the stated risk that it is wrong).
  ConfidenceCalibration calibration;
  double localized_confidence = 0.995;
  // The posterior the Bayes matcher needs to declare a pose (replaces the study's): the one
  // whose calibrated confidence is localized_confidence.
  double bayes_threshold = 0.995;
  // Once localized: the belief under which a pose given up is LOST (above it: RECOVERING).
  double bayes_lost_threshold = 0.05;
  // A false door must fit in the wall that holds it (recovery::BayesSettings::false_door_fit).
  bool bayes_false_door_fit = false;
  // The rest of a wall past a false door may run on over missed doors
  // (recovery::BayesSettings::w2_over_missed_doors; replaces the study's). Optional: off.
  bool bayes_w2_over_missed_doors = false;
  // A wall over missed doors may end in a first part as short as the noise reads it
  // (recovery::BayesSettings::first_part_in_noise; replaces the study's). Optional: off.
  bool bayes_first_part_in_noise = false;
  // Missed doors one sensed wall may span (recovery::BayesSettings::max_missed_doors;
  // replaces the study's): in a row of doors the pipeline misses several in a row.
  int bayes_max_missed_doors = 2;
  // The direction of travel along the rings from the odometer's sign
  // (LocalizerConfig::direction_from_travel). A fact of the robot, but set with the model:
  // the calibration is fitted with it or without. Optional: off.
  bool bayes_direction_from_travel = false;
};

// The observation model for a map whose hallways are narrow: the landmark pipeline reads a
// wall seen from nearer than the Engineering Building's 120 in hallways (more doors cut by
// the image side, a faster sweep of the wall per foot), so its errors were measured there.
struct NarrowMapSettings {
  // A map is narrow when its widest hallway (MapHallwayWidthIn) is at most this.
  double max_hallway_width_in = 0.0;
  ObservationSettings observation;
};

// Which of the configured observation models ForMap chose.
enum class ObservationFor : std::uint8_t { kDefault, kMarkedMap, kNarrowMap, kOwnMap };
const char* ObservationForName(ObservationFor o);

// The localizer process's settings (configs/localizer.yaml). The Bayes matcher's
// observation model is read from the files named here once the map is known
// (MakeLocalizerConfig).
struct LocalizerSettings {
  LocalizerConfig localizer;   // everything but the Bayes model
  map::HallwayViewConfig view;
  // The observation model for a map whose doors carry no surveyed marks, the one for a map
  // whose doors do (Table 6.8), the one for a map of narrow hallways and a floor's own (its
  // calibration measured on runs of that floor), where they differ: ForMap picks one.
  ObservationSettings observation;
  std::optional<ObservationSettings> on_marked_maps;
  std::optional<NarrowMapSettings> on_narrow_maps;
  std::map<std::string, ObservationSettings> on_maps;  // by the map's name (MapInfo::name)
  // Set by ForMap: which model `observation` is.
  ObservationFor observation_for = ObservationFor::kDefault;
  std::string study_file;
  double publish_rate_hz = 2.0;
  // The probability that a sensed edge is one the error model cannot explain (replaces the
  // study's).
  double bayes_outlier = 1e-4;
  // Further edges over which the best place must keep the threshold.
  int bayes_confirm_edges = 0;
  double bayes_confirm_silent_in = 0.0;
  // Once localized: the belief the pose must keep to stay LOCALIZED (below it the pose is
  // given up: LOST or RECOVERING, ObservationSettings::bayes_lost_threshold), and the
  // probability per edge that the robot was carried anywhere
  // (recovery::BayesSettings::kidnap_per_edge).
  double bayes_keep_threshold = 0.9;
  double bayes_kidnap_per_edge = 0.0;
  // Further edges the evidence must stay against a pose given up before LOST is said
  // (LocalizerConfig::lost_confirm_edges).
  int bayes_lost_confirm_edges = 0;
  // Once localized, the silence past the last sensed edge tests the pose too
  // (LocalizerConfig::silence_tests_pose).
  bool bayes_silence_tests_pose = false;
  bool bayes_best_with_neighbours = false;
};

// Whether any door of `m` carries a surveyed mark (DoorMarkOfPattern is not kUnknown).
bool HasSurveyedMarks(const map::Map& m);

// The width of the widest hallway of `m` among its rings that give one (map format 2's
// `width_in`); `otherwise` when none does (the view's default hallway width).
double MapHallwayWidthIn(const map::Map& m, double otherwise);

// `settings` with the observation model for `m`: the on_maps entry named as `m` is, where
// there is one; else on_marked_maps where it is set and `m` has surveyed marks; else
// on_narrow_maps where it is set and `m`'s widest hallway is within its
// max_hallway_width_in; else the default one. observation_for says which.
LocalizerSettings ForMap(LocalizerSettings settings, const map::Map& m);

// Reads the `localizer` section; every key required but the `on_marked_maps`,
// `on_narrow_maps` (its `max_hallway_width_in` with the others) and `on_maps` blocks (a block
// of the same keys under each map name), unknown keys rejected (InputError with file, line
// and key).
LocalizerSettings LoadLocalizerSettings(const StrictYaml& section);

// The localizer's configuration for matching against `matched` (the hallway view of the
// map): for the Bayes method, the observation model from `settings.observation`'s error
// model and the study file (their errors are InputErrors naming those files). Call it with
// ForMap's settings.
LocalizerConfig MakeLocalizerConfig(const LocalizerSettings& settings, const map::Map& matched);

}  // namespace stickrep::localizer
