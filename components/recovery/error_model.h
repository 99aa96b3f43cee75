#pragma once

// The sensing-error model of the simulation study (§6.4.2, Table 6.10) and the study's own
// sensing and matching parameters (configs/study.yaml). Two files, two loaders:
//
//   configs/error_model_paper.yaml  `error_model:` the fused confusion of the landmark
//       pipeline — true doors sensed correct / mis-sized / missed, false doors in walls.
//       A measured file in the same schema can replace it (stickrep-study --error-model).
//   configs/study.yaml              `study:` ultrasonic width error, wheel (odometry) error,
//       matching tolerances, the Figure 6.4 relaxation steps, frame rate and speed, limits,
//       and the Bayes filter's settings.
//
// Both loaders are strict (every key checked) and throw stickrep::InputError naming file,
// line and key.

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "stickrep/map.h"
#include "stickrep/sequence_matcher.h"

namespace stickrep::recovery {

inline constexpr int kDoorClasses = map::kDoorClassCount;
// A door sensed this much narrower than its class (a double door's one leaf) has left the
// rest of its width to a wall beside it (ErrorModel::leaf_wall_before/after); a smaller
// mis-sizing is lost in the walls' odometry noise.
inline constexpr double kLeafDeficitIn = 12.0;
using ClassVector = std::array<double, kDoorClasses>;
using ClassMatrix = std::array<ClassVector, kDoorClasses>;

// Table 6.10 as a generative model of what the landmark pipeline reports (Figure 6.2,
// step 2). Rates are per true door (they sum to 1) and per wall edge.
struct ErrorModel {
  std::string source = "Table 6.10, Walsh";
  double door_correct = 0.8367;     // true positives, sensed with their class
  double door_missized = 0.1020;    // true positives sensed with a wrong class
  double door_missed = 0.0612;      // false negatives
  double wall_false_door = 0.1591;  // false positives, per wall edge
  // False doors per inch of wall, where the file gives it (the walls of a row keep
  // in_row's rate per wall). A wall of length L then holds a false door with probability
  // 1 - exp(-rate L), and the rest of a wall past a false door may hold another alike; without
  // it every wall holds one at most, at wall_false_door. The pipeline reads a false door on a
  // stretch of wall (a panel, a poster, a shadow), so a long wall holds more: measured on the
  // science hall, 16 % of the walls of 60-120 in and 123 % of those of 480-960 in
  // (docs/whereami.md). The study's sampler draws them alike (SensedStream).
  std::optional<double> wall_false_door_per_in;
  // With wall_false_door_per_in, the most false doors one wall holds (a false door past
  // that many is left to the outlier). Without it a wall holds any number: each rest of a
  // wall past a false door may hold another.
  std::optional<int> wall_false_doors_max;
  // Per true class, its own door rates where they differ from the ones above (a double door
  // is read as one leaf far more often than a single door is mis-sized). Each sums to 1.
  struct DoorRates {
    double correct = 0, missized = 0, missed = 0;
  };
  std::map<map::DoorClass, DoorRates> by_class;
  // Doors in a row and the walls under map::kRowWallIn between two doors (map::InDoorRow):
  // their own rates where the file gives them (per class, each summing to 1; a class not
  // listed keeps its rates above, as does a missing false-door rate). With it, the rates
  // above are those of the doors alone and of the other walls. Rows of doors are where the
  // pipeline's errors come together (a double door between two panels read leaf by leaf,
  // a false door on the panel between two casings).
  struct InRow {
    std::optional<double> wall_false_door;
    std::map<map::DoorClass, DoorRates> by_class;
    // The same walls' false-door rate by the door before the wall in the direction of
    // travel: missed, or seen (with its class or not). Where the pipeline misses a door of
    // a row it reads the panel between the casings beyond it as a door instead (measured
    // on the Engineering Building: 70 % of these walls after a missed door, 6 % between two
    // doors seen), so the two errors come together. Both or neither; without them the wall
    // keeps wall_false_door whatever came before it.
    std::optional<double> wall_false_door_after_missed, wall_false_door_after_seen;
    // A door of a row by the door before it, across the short wall between them (in the
    // direction of travel): its missed rate after a missed door and after a seen one, per
    // class; its other rates (correct, mis-sized) keep their shares of what is left. The
    // pipeline misses the doors of a row together (measured on the Engineering Building: a
    // 36 in door of a row missed 43 % of the time after a missed door, 4 % after a seen
    // one; doors not in a row are missed as often whatever came before). Both or neither;
    // a class listed in neither keeps its by_class rate whatever came before.
    std::map<map::DoorClass, double> door_missed_after_missed, door_missed_after_seen;
  };
  std::optional<InRow> in_row;
  // A sensed wall that runs over missed doors (the jambs of a door not seen are no sensed
  // boundary) is read longer than the true edges it spans, and more loosely, than the
  // odometry alone makes a wall of that length (SensingNoise::WallSigmaIn): per missed door,
  // a mean of `bias_in` and a further standard deviation of `sigma_in` (measured on the
  // Engineering Building: +3.5 in, sd 3.1 in, against 1 in for a wall between two doors
  // read right). Absent: such a wall is weighed as the true edges' length.
  struct WallOverMissedDoor {
    double bias_in = 0.0;
    double sigma_in = 0.0;
  };
  std::optional<WallOverMissedDoor> wall_over_missed_door;
  // Per true class, where its mis-sized sightings go (sensed class -> probability). A class
  // not listed goes to its neighbouring classes equally (DefaultMissizedTargets).
  std::map<map::DoorClass, std::map<map::DoorClass, double>> missized_to;
  // The class distribution of false doors; empty: the map's door-class frequencies.
  std::map<map::DoorClass, double> false_door_classes;
  // A mis-sized door read at least kLeafDeficitIn narrower than it is (a double door read as
  // one leaf): where the rest of its width went, as shares of those reads. The other leaf
  // read as a second door (`leaf_split`; of those, `leaf_sliver` with a sliver of wall, the
  // meeting stiles, between the two), or the sensed wall before or after it longer by the
  // missing width. Not in Table 6.10 (the paper counts frames, not assembled edges); all 0:
  // every such read leaves its neighbours as they are.
  double leaf_split = 0.0;
  double leaf_sliver = 0.0;
  double leaf_wall_before = 0.0;
  double leaf_wall_after = 0.0;
  // How the leaf's mark is read (Table 6.8's supplemental marks, vision/door_mark_reader.h):
  // per true mark of the door (plain, window, poster; a false door under `false_door`), the
  // shares of its reads that were unknown, plain, window and poster (each row sums to 1), for
  // doors sensed with their class (`marks:`) and for mis-sized doors (`marks_missized:`; a
  // double door read as one leaf is framed by other edges than its jambs, and its mark read
  // between them). Empty: marks are not modelled and the filter ignores them (the paper's).
  using MarkRow = std::array<double, map::kDoorMarkCount>;  // indexed by map::DoorMark
  std::map<map::DoorMark, MarkRow> mark_read;
  std::map<map::DoorMark, MarkRow> mark_read_missized;  // a row missing: mark_read's
  std::optional<MarkRow> false_door_marks;
  bool HasMarks() const { return !mark_read.empty(); }

  // The paper's rates (Table 6.10).
  static ErrorModel Paper() { return ErrorModel{}; }
  // No sensing error at all (§6.4.1).
  static ErrorModel None();
  bool IsErrorFree() const {
    return door_missized == 0.0 && door_missed == 0.0 && wall_false_door == 0.0;
  }
  // Throws std::invalid_argument naming the bad field.
  void Validate() const;
};

// Loads the `error_model:` file; throws InputError (file:line:key) on any problem.
ErrorModel LoadErrorModel(const std::string& path);
ErrorModel ParseErrorModel(const std::string& text, const std::string& name);
// The model as an `error_model:` file that LoadErrorModel reads back; `comment` (lines
// without '#') goes on top.
std::string FormatErrorModelYaml(const ErrorModel& model, const std::string& comment);

// The classes a mis-sized door of class `c` goes to when the file does not say: the
// neighbouring single-door widths (30-32-36-40), or for a double door the other double.
std::vector<map::DoorClass> DefaultMissizedTargets(map::DoorClass c);

// ErrorModel resolved against one map: full matrices, ready for sampling and for the
// Bayes filter's observation model.
struct Confusion {
  double correct = 0, missized = 0, missed = 0, false_door = 0;
  // Per true class: ErrorModel::by_class, or the rates above.
  ClassVector class_correct{}, class_missized{}, class_missed{};
  // The same for doors in a row, and the false doors of a wall between two doors of a row
  // (ErrorModel::in_row; the rates above where the model has none).
  ClassVector row_correct{}, row_missized{}, row_missed{};
  double row_false_door = 0;
  bool row_false_door_own = false;  // the model gives the walls of a row their own rate
  // ErrorModel::InRow::wall_false_door_after_seen / _after_missed, when the model has them.
  double row_false_door_after_seen = 0, row_false_door_after_missed = 0;
  bool row_false_door_by_before = false;
  // ErrorModel::wall_over_missed_door, 0 without it: a sensed wall over `m` missed doors
  // reads m * missed_wall_bias_in longer, with m * missed_wall_var_in2 more variance.
  double missed_wall_bias_in = 0, missed_wall_var_in2 = 0;
  // The rates of a map door of class index `k`, in a row or not (MatchIndex::in_row).
  double Correct(int k, bool row) const { return row ? row_correct[k] : class_correct[k]; }
  double Missized(int k, bool row) const { return row ? row_missized[k] : class_missized[k]; }
  double Missed(int k, bool row) const { return row ? row_missed[k] : class_missed[k]; }
  // The false-door rate of a map wall, between two doors of a row or not.
  double FalseDoor(bool row) const { return row ? row_false_door : false_door; }
  // ErrorModel::wall_false_door_per_in, 0 when the model rates false doors per wall.
  double false_door_per_in = 0;
  // The probability that a map wall of `len_in` (between two doors of a row or not) holds a
  // false door: by its length where the model rates false doors per inch (but a row's short
  // walls with a rate of their own), else per wall. A row's wall takes the rate after a
  // missed or a seen door where the model has them and the door before it is known.
  enum class Before : std::uint8_t { kUnknown, kDoorSeen, kDoorMissed };
  double FalseDoorIn(double len_in, bool row, Before before = Before::kUnknown) const;
  // ErrorModel::InRow::door_missed_after_missed / _after_seen by class index (row_missed
  // where the model has none), and whether the model has them.
  ClassVector row_missed_after_missed{}, row_missed_after_seen{};
  bool row_missed_by_before = false;
  // The missed rate of a door of a row of class index `k` by the door before it, and the
  // factor its read rates (Correct, Missized in a row) take with it: what is left beside
  // that missed rate against what is left beside row_missed. kUnknown: row_missed and 1.
  double RowMissed(int k, Before before) const;
  double RowReadFactor(int k, Before before) const;
  // Whether the rest of a wall past a false door may hold another (the per-inch model).
  bool FalseDoorsChain() const { return false_door_per_in > 0.0; }
  // ErrorModel::wall_false_doors_max, 0 for any number.
  int false_doors_max = 0;
  // Whether the rest of a wall past `held` false doors may hold another.
  bool AnotherFalseDoor(int held) const {
    return FalseDoorsChain() && (false_doors_max <= 0 || held < false_doors_max);
  }
  ClassMatrix missized_to{};  // [true][sensed], each row sums to 1
  ClassVector false_class{};  // sums to 1
  ClassVector map_prior{};    // the map's door-class frequencies (sum 1, or all 0)
  // ErrorModel::leaf_split, leaf_sliver, leaf_wall_before, leaf_wall_after
  double leaf_split = 0, leaf_sliver = 0, leaf_before = 0, leaf_after = 0;
  // P(read mark | the door's mark), [true][read] by map::DoorMark, and for a false door;
  // `marks` false when the model has none (every factor is then 1).
  bool marks = false;
  // Row kUnknown is a map door whose mark the map does not give: the rows of the marks
  // mixed as the map's surveyed doors have them (or equally, over the model's rows, on a
  // map with none surveyed).
  std::array<ErrorModel::MarkRow, map::kDoorMarkCount> mark_read{}, mark_read_missized{};
  ErrorModel::MarkRow false_mark{};
  // The factor a door read with mark `read` gets at a map door of mark `truth`, its class
  // read right or not; at a false door. 1 when marks are not modelled.
  double MarkLikelihood(map::DoorMark read, map::DoorMark truth, bool class_right = true) const;
  double FalseDoorMarkLikelihood(map::DoorMark read) const;
};
Confusion Resolve(const ErrorModel& model, const map::MatchIndex& index);

// Where the measured width of a door of each class may lie when the classifier assigned
// it that class: the Bayes class regions of Table 4.1 plus door30 (docs/sensing.md).
struct ClassRegion {
  double lo_in = 0, hi_in = 0;
};

// Ultrasonic width error, wheel error and the timing of the study (configs/study.yaml).
struct SensingNoise {
  // Short Side width error, relative (docs/sensing.md: sigma fitted to Table 4.1).
  double width_sigma_rel = 0.0227;
  std::array<ClassRegion, kDoorClasses> class_region_in{};
  // Placement error of one jamb along the wall, inches.
  double jamb_sigma_in = 0.6;
  // Odometry: a per-run scale error (wheel diameter, tyre wear) and a random walk whose
  // variance grows with the distance travelled (slip), so the error of a measured wall
  // grows with its length (§6.3 step 6.1.1.1).
  double wheel_scale_sigma_rel = 0.01;
  double wheel_walk_sigma_in_per_sqrt_in = 0.15;
  static SensingNoise None();
  // Standard deviation of a measured wall of this true length (both jambs, scale, walk).
  double WallSigmaIn(double length_in) const;
};

// Settings of the Bayes filter (SPEC §5) that are not the confusion itself.
struct BayesSettings {
  double threshold = 0.995;         // posterior of the best pose needed to report it
  double outlier = 1e-4;            // probability that a sensed edge is unexplained
  int max_missed_doors = 2;         // missed doors one sensed wall may span
  double angle_tolerance_deg = 20;  // sensed corner angle vs map
  // Further edges over which the best place must keep the threshold before it is reported
  // (0: at once, as the study does).
  int confirm_edges = 0;
  // ... and then over this much silence (SetSilence) after the edge that brought it there,
  // or over one more edge: the place's next door or corner, if it is near, must not be
  // missing (0: at once).
  double confirm_silent_in = 0.0;
  // Steps in a wall the follower passes straight (a pilaster's or shallow recess's sides up
  // to this long): a reversal's distance does not run along them. The localizer sets it to
  // its hallway view's max_step_in.
  double max_step_in = 36.0;
  // A corridor's open end (map::IsOpenEnd): the wall sensed last before it runs on as far
  // as the next thing seen outside, up to this much past the wall's end (across the open
  // end and the corridor beyond: two 120 in hallways).
  double open_end_reach_in = 240.0;
  // The probability that the robot was carried anywhere on the floor (kidnapped, or its
  // odometry lost beyond repair) before a sensed edge: that share of the belief starts again
  // from the prior at every edge, so belief held at a wrong place drains to the right one as
  // the evidence against it comes. 0: never (the study's runs). The localizer applies it
  // only while it holds a pose (BayesLocalizer::SetKidnapShare).
  double kidnap_per_edge = 0.0;
  // A false door must fit in the wall that holds it: the first part W1 of a wall leaves room
  // for the narrowest door, and the false door sensed after it fits in the rest, within the
  // odometry and jamb noise (BayesLocalizer::Fits). Off, W1 is uniform over the whole wall
  // and any false door is taken after it, which leaves belief on "a false door inside the
  // wall just sensed" at every door (docs/whereami.md, "The doors' marks"). Off in the
  // study, which was measured without it, unless its config asks (bayes.false_door_fit).
  bool false_door_fit = false;
  // The rest of a wall past a false door (W2) may run on over missed doors into the walls
  // beyond, as a sensed wall before a false door may (BayesLocalizer::
  // NextSecondPartOverMissedDoors). The study's sampler makes such walls (a false door and
  // a missed door beside it merge their walls); in a row of doors the live pipeline reads
  // them all along (a missed door, the panel beside it as a door). Off: only the outlier
  // explains them.
  bool w2_over_missed_doors = false;
  // A sensed wall over missed doors may end in the first part of the wall after them however
  // short that part is, down to two of the wall's sigmas under nothing (BayesLocalizer::
  // RunOnOverMissedDoors). Off, a first part must read longer than nothing, and a false door
  // just past a missed door (a row's panel beside a missed double door) is the outlier's
  // about half the time: on reads drawn from its own model the filter was then wrong 1.21 %
  // of the time at the posterior 0.995 instead of 0.62 % (docs/whereami.md, "The study's
  // sampler draws what the filter weighs"). On the live reads it changed nothing measured,
  // so the shipped settings leave it off.
  bool first_part_in_noise = false;
  // The best place is the (edge, direction) whose belief with its two neighbours along the
  // ring (the same direction) is the most, and that sum is its probability: a place is
  // judged right when the robot is in its edge or a neighbour (a node may be crossed as the
  // pose is published), and the filter often splits its belief between neighbours over a
  // door it cannot tell from a false one in the wall beside it. Off: the single (edge,
  // direction) with the most. Measured and off in the shipped configs (docs/whereami.md,
  // "The best place with its neighbours").
  bool best_with_neighbours = false;
};

struct StudyConfig {
  std::string source;
  double speed_ftps = 2.6;      // §6.3, the Labmate base
  double frame_period_s = 0.2;  // §6.3
  SensingNoise noise;
  // Tolerance of the level-0 match (Figure 6.4's 0 %): what odometry and jamb placement
  // deliver inside the envelope. Relaxation adds to metric_rel.
  map::MatchTolerance base_tolerance{0.06, 4.0, 20.0};
  std::vector<double> relaxation_steps{0.10, 0.20};  // Figure 6.4
  int first_frame_edges = 2;  // §6.6.1: a failure this early counts as "in the first frame"
  int max_edges = 400;        // give-up limit of one run: "did not converge"
  BayesSettings bayes;

  double FrameTravelIn() const { return speed_ftps * 12.0 * frame_period_s; }
  void Validate() const;  // throws std::invalid_argument
};

StudyConfig LoadStudyConfig(const std::string& path);
StudyConfig ParseStudyConfig(const std::string& text, const std::string& name);
// Class regions of docs/sensing.md (DefaultBoundaries: Table 4.1 + door30).
std::array<ClassRegion, kDoorClasses> DefaultClassRegions();

}  // namespace stickrep::recovery
