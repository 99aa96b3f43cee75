#include "localizer/localizer_config.h"

#include "common/config_paths.h"
#include "localizer/sensed_doors.h"
#include "recovery/error_model.h"
#include "stickrep/sequence_matcher.h"

namespace stickrep::localizer {
namespace {

// The keys of one observation model (ObservationSettings) in `c`; `keep_threshold` is the
// belief a held pose must keep, which must lie between the LOST threshold and the posterior
// the bar needs.
ObservationSettings LoadObservation(const StrictYaml& c, double keep_threshold) {
  ObservationSettings o;
  o.error_model_file = ResolvePath(c.Get<std::string>("error_model_file"), c.file());
  o.calibration.slope = c.Get<double>("confidence_calibration_slope", 0.05, 20.0);
  o.calibration.offset = c.Get<double>("confidence_calibration_offset", -20.0, 20.0);
  o.localized_confidence = c.Get<double>("localized_confidence", 0.5, 0.999999);
  o.bayes_threshold = o.calibration.PosteriorFor(o.localized_confidence);
  if (o.bayes_threshold > 0.999999) {
    c.Fail("localized_confidence", "needs a posterior of " + std::to_string(o.bayes_threshold) +
                                       " under this calibration: more than the filter's 0.999999");
  }
  if (keep_threshold > o.bayes_threshold) {
    c.Fail("localized_confidence", "needs a posterior of " + std::to_string(o.bayes_threshold) +
                                       ", under bayes_keep_threshold (" +
                                       std::to_string(keep_threshold) + ")");
  }
  o.bayes_lost_threshold = c.Get<double>("bayes_lost_threshold", 0.0, 0.999999);
  if (o.bayes_lost_threshold > keep_threshold) {
    c.Fail("bayes_lost_threshold",
           "must not be above bayes_keep_threshold (" + std::to_string(keep_threshold) + ")");
  }
  o.bayes_false_door_fit = c.Get<bool>("bayes_false_door_fit");
  o.bayes_w2_over_missed_doors = c.GetOr<bool>("bayes_w2_over_missed_doors", false);
  o.bayes_first_part_in_noise = c.GetOr<bool>("bayes_first_part_in_noise", false);
  o.bayes_max_missed_doors = c.Get<int>("bayes_max_missed_doors", 0, 4);
  o.bayes_direction_from_travel = c.GetOr<bool>("bayes_direction_from_travel", false);
  return o;
}

}  // namespace

bool HasSurveyedMarks(const map::Map& m) {
  for (const map::Ring& ring : m.rings()) {
    for (const map::Edge& e : ring.edges) {
      if (e.IsDoor() && map::DoorMarkOfPattern(e.pattern) != map::DoorMark::kUnknown) return true;
    }
  }
  return false;
}

const char* ObservationForName(ObservationFor o) {
  switch (o) {
    case ObservationFor::kMarkedMap:
      return "the map's doors carry surveyed marks";
    case ObservationFor::kNarrowMap:
      return "the map's hallways are narrow";
    case ObservationFor::kOwnMap:
      return "the map's own, measured on it";
    case ObservationFor::kDefault:
      break;
  }
  return "the default model";
}

double MapHallwayWidthIn(const map::Map& m, double otherwise) {
  std::optional<double> widest;
  for (const map::Ring& ring : m.rings()) {
    if (ring.width_in && (!widest || *ring.width_in > *widest)) widest = ring.width_in;
  }
  return widest.value_or(otherwise);
}

LocalizerSettings ForMap(LocalizerSettings settings, const map::Map& m) {
  settings.observation_for = ObservationFor::kDefault;
  const auto own = settings.on_maps.find(m.info().name);
  if (own != settings.on_maps.end()) {
    settings.observation = own->second;
    settings.observation_for = ObservationFor::kOwnMap;
  } else if (settings.on_marked_maps && HasSurveyedMarks(m)) {
    settings.observation = *settings.on_marked_maps;
    settings.observation_for = ObservationFor::kMarkedMap;
  } else if (settings.on_narrow_maps && MapHallwayWidthIn(m, settings.view.hallway_width_in) <=
                                            settings.on_narrow_maps->max_hallway_width_in) {
    settings.observation = settings.on_narrow_maps->observation;
    settings.observation_for = ObservationFor::kNarrowMap;
  }
  settings.on_marked_maps.reset();
  settings.on_narrow_maps.reset();
  settings.on_maps.clear();
  return settings;
}

LocalizerSettings LoadLocalizerSettings(const StrictYaml& c) {
  LocalizerSettings s;
  LocalizerConfig& config = s.localizer;
  const std::string method = c.Get<std::string>("method");
  if (method == "bayes") {
    config.method = MatchMethod::kBayes;
  } else if (method == "deterministic") {
    config.method = MatchMethod::kDeterministic;
  } else {
    c.Fail("method", "'" + method + "' is not one of: deterministic, bayes");
  }
  s.study_file = ResolvePath(c.Get<std::string>("study_file"), c.file());
  config.tolerance.metric_rel = c.Get<double>("metric_tolerance_rel", 0.0, 1.0);
  config.tolerance.metric_abs_in = c.Get<double>("metric_tolerance_abs_in", 0.0, 120.0, "in");
  config.tolerance.angle_deg = 20.0;  // corners are sensed as turns of the odometry heading
  config.assembler.same_door_in = c.Get<double>("same_door_in", 1.0, 60.0, "in");
  config.assembler.out_of_view_in = c.Get<double>("out_of_view_in", 6.0, 240.0, "in");
  config.assembler.min_frames = c.Get<int>("min_frames", 1, 20);
  config.assembler.min_wall_in = c.Get<double>("min_wall_in", 0.0, 60.0, "in");
  config.assembler.silent_margin_in = c.Get<double>("silent_margin_in", 0.0, 240.0, "in");
  config.max_hypotheses = c.Get<int>("max_hypotheses", 1, 64);
  s.view.max_step_in = c.Get<double>("max_step_in", 0.0, 120.0, "in");
  s.view.max_bend_deg = c.Get<double>("max_bend_deg", 0.0, 60.0, "deg");
  s.view.sensed_door_class = SensedDoorClass;
  s.view.hallway_width_in = c.Get<double>("hallway_width_in", 24.0, 600.0, "in");
  s.view.max_recess_in = c.Get<double>("max_recess_in", 0.0, 600.0, "in");
  s.view.door_view_margin_in = c.Get<double>("door_view_margin_in", 0.0, 60.0, "in");
  s.publish_rate_hz = c.Get<double>("publish_rate_hz", 0.1, 50.0, "Hz");
  s.bayes_outlier = c.Get<double>("bayes_outlier", 1e-9, 0.5);
  s.bayes_confirm_edges = c.Get<int>("bayes_confirm_edges", 0, 20);
  s.bayes_confirm_silent_in = c.Get<double>("bayes_confirm_silent_in", 0.0, 600.0, "in");
  s.bayes_keep_threshold = c.Get<double>("bayes_keep_threshold", 0.0, 0.999999);
  s.bayes_kidnap_per_edge = c.Get<double>("bayes_kidnap_per_edge", 0.0, 0.5);
  s.bayes_lost_confirm_edges = c.Get<int>("bayes_lost_confirm_edges", 0, 10);
  s.bayes_silence_tests_pose = c.Get<bool>("bayes_silence_tests_pose");
  s.bayes_best_with_neighbours = c.Get<bool>("bayes_best_with_neighbours");
  s.observation = LoadObservation(c, s.bayes_keep_threshold);
  if (c.Has("on_marked_maps")) {
    const StrictYaml marked = c.Child("on_marked_maps");
    s.on_marked_maps = LoadObservation(marked, s.bayes_keep_threshold);
    marked.Finish();
  }
  if (c.Has("on_narrow_maps")) {
    const StrictYaml narrow = c.Child("on_narrow_maps");
    NarrowMapSettings n;
    n.max_hallway_width_in = narrow.Get<double>("max_hallway_width_in", 24.0, 600.0, "in");
    n.observation = LoadObservation(narrow, s.bayes_keep_threshold);
    narrow.Finish();
    s.on_narrow_maps = n;
  }
  if (c.Has("on_maps")) {
    const StrictYaml maps = c.Child("on_maps");
    for (const std::string& name : maps.Keys()) {
      const StrictYaml own = maps.Child(name);
      s.on_maps[name] = LoadObservation(own, s.bayes_keep_threshold);
      own.Finish();
    }
    maps.Finish();
  }
  c.Finish();
  return s;
}

LocalizerConfig MakeLocalizerConfig(const LocalizerSettings& settings, const map::Map& matched) {
  LocalizerConfig config = settings.localizer;
  if (config.method == MatchMethod::kBayes) {
    // The observation model: the landmark pipeline's confusion and the sensing noise.
    const ObservationSettings& o = settings.observation;
    const recovery::ErrorModel errors = recovery::LoadErrorModel(o.error_model_file);
    const recovery::StudyConfig study = recovery::LoadStudyConfig(settings.study_file);
    const map::MatchIndex index(matched);
    config.bayes = recovery::BayesModel{recovery::Resolve(errors, index), study.noise, study.bayes};
    config.bayes.settings.threshold = o.bayes_threshold;
    config.bayes.settings.outlier = settings.bayes_outlier;
    config.bayes.settings.confirm_edges = settings.bayes_confirm_edges;
    config.bayes.settings.confirm_silent_in = settings.bayes_confirm_silent_in;
    config.bayes.settings.kidnap_per_edge = settings.bayes_kidnap_per_edge;
    config.bayes.settings.false_door_fit = o.bayes_false_door_fit;
    config.bayes.settings.w2_over_missed_doors = o.bayes_w2_over_missed_doors;
    config.bayes.settings.first_part_in_noise = o.bayes_first_part_in_noise;
    config.bayes.settings.max_missed_doors = o.bayes_max_missed_doors;
    config.bayes.settings.best_with_neighbours = settings.bayes_best_with_neighbours;
    config.keep_threshold = settings.bayes_keep_threshold;
    config.calibration = o.calibration;
    config.lost_threshold = o.bayes_lost_threshold;
    config.lost_confirm_edges = settings.bayes_lost_confirm_edges;
    config.silence_tests_pose = settings.bayes_silence_tests_pose;
    config.direction_from_travel = o.bayes_direction_from_travel;
    config.bayes.settings.max_step_in = settings.view.max_step_in;
  }
  return config;
}

}  // namespace stickrep::localizer
