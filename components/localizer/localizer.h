#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "localizer/confidence_calibration.h"
#include "localizer/edge_assembler.h"
#include "localizer/pose_tracker.h"
#include "recovery/bayes_localizer.h"
#include "stickrep/hallway_view.h"
#include "stickrep/map.h"
#include "stickrep/sequence_matcher.h"

namespace stickrep::localizer {

enum class Status { kRecovering, kLocalized, kLost };
const char* ToString(Status s);

// One place the robot may be: just past edge `edge` of ring `ring`, travelling in `dir`.
struct Hypothesis {
  int ring = 0;
  int edge = 0;            // the edge the robot is in now (ring-local index)
  int dir = +1;            // +1: ring order
  double offset_in = 0.0;  // how far into that edge
  double x_in = 0.0, y_in = 0.0, heading_rad = 0.0;  // on the wall, building frame
  double probability = 0.0;
};

struct PoseEstimate {
  Status status = Status::kRecovering;
  std::size_t candidates = 0;
  int edges_sensed = 0;            // in the current sequence
  std::vector<Hypothesis> hypotheses;  // best first; empty while nothing is sensed
  // Bayes: the best place's calibrated confidence (the hypotheses carry the filter's raw
  // posterior); deterministic: 1 / candidates.
  double confidence = 0.0;
  std::string message;
};

// A hypothesis `offset_in` into edge `edge` of ring `ring_index` (from the node behind in
// travel direction `dir`), with its place and heading in the building frame.
Hypothesis PlaceOnMap(const map::Map& map, int ring_index, int edge, int dir, double offset_in,
                      double probability);
// A hypothesis on a hallway view (matching runs there) as a place on the view's own map.
Hypothesis OnOriginalMap(const map::HallwayView& view, const Hypothesis& h);

// How sensed edges are matched against the map.
enum class MatchMethod {
  kDeterministic,  // string matching with tolerance; discard and restart on failure (§6.7)
  kBayes,          // discrete Bayes filter over (edge, direction) (SPEC §5)
};

struct LocalizerConfig {
  MatchMethod method = MatchMethod::kDeterministic;
  EdgeAssemblerConfig assembler;
  // The Bayes filter's observation model (configs/error_model_*.yaml, configs/study.yaml).
  recovery::BayesModel bayes;
  // Metric tolerance of the wall lengths: odometry and jamb placement are not exact.
  map::MatchTolerance tolerance{0.10, 6.0, -1.0};
  int max_hypotheses = 64;
  // Pose maintenance once localized (§3.3).
  PoseTrackerConfig tracker;
  // Bayes: once localized, the filter keeps weighing every sensed edge, and the pose stays
  // LOCALIZED while the filter's belief in it (the tracked edge or a neighbour, its
  // direction) is at least keep_threshold; below, it is LOST when under lost_threshold and
  // RECOVERING otherwise, and the filter, which has kept the alternatives, recovers from
  // there.
  double keep_threshold = 0.9;
  double lost_threshold = 0.05;
  // Further sensed edges after which the belief in a pose given up must still be under
  // lost_threshold, and no higher than when it was given up (those edges against it too),
  // before LOST is said (RECOVERING meanwhile); 0: LOST at once.
  int lost_confirm_edges = 0;
  // Once localized, what has not been sensed since the last edge is weighed too, as in
  // recovery (a door the held place has by now that did not come): it can give the pose up
  // (RECOVERING; LOST only if the next edges are against it too), never move it.
  bool silence_tests_pose = false;
  // Bayes: the direction of travel along the rings follows from the odometer's sign. The
  // camera looks left of the base's heading (+90°, §6.4.2) and the base drives forward or
  // backward with it on the wall (§6.3); a ring is listed walking with its wall on the right
  // (maps/README.md), so driving forward walks it against its order. A first edge, and belief
  // that starts again from the prior, then goes to that direction alone. Off: either.
  bool direction_from_travel = false;
  // Bayes: the published confidence from the filter's posterior (identity by default).
  ConfidenceCalibration calibration;
};

// The localizer's logic, free of DDS: door sightings and the odometer in, a pose estimate
// out. Edges are matched incrementally against every ring position in both directions
// (§6.1). Deterministic: when no candidate is left the sequence is discarded and a new one
// started (§6.7), and one candidate is the pose. Bayes: the posterior over (edge,
// direction) absorbs inserted, missed and mis-sized doors, and the pose is declared once
// the best hypothesis passes the threshold. Once localized, the pose is maintained by
// confirming each anticipated edge (§3.3); too many misses — a kidnapped robot — turn the
// status to LOST and a full recovery starts.
class Localizer {
 public:
  Localizer(const map::Map& map, LocalizerConfig config = {});

  void AddSighting(const DoorSighting& s) { assembler_.AddSighting(s); }
  // Distance from the base centre to the camera's wall (coaxial sonar), for corners.
  void SetWallRange(double range_in) { assembler_.SetWallRange(range_in); }
  // Advances the odometer and heading; true if the estimate changed (edges were matched).
  bool Advance(double odometer_in, double heading_rad = 0.0);
  const PoseEstimate& estimate() const { return estimate_; }
  const LocalizerConfig& config() const { return config_; }
  std::uint64_t restarts() const { return restarts_; }
  std::uint64_t losses() const { return losses_; }
  std::uint64_t edges_total() const { return edges_total_; }
  // The last LOCALIZED pose given up: where, the filter's belief in it then, and whether it
  // was declared LOST (belief under lost_threshold, and still under it and not risen
  // lost_confirm_edges edges on) rather than RECOVERING.
  struct GivenUp {
    int ring = 0;
    int edge = 0;
    int dir = +1;
    double belief = 0.0;
    bool lost = false;
    std::uint64_t serial = 0;  // 1 for the first pose given up, and so on
    // The belief in it, carried on by the edges sensed since, when LOST was last weighed
    // again (none if it never was: LOST said at once, or RECOVERING with the belief over
    // lost_threshold).
    std::optional<double> belief_on;
  };
  const std::optional<GivenUp>& given_up() const { return given_up_; }
  // The edges sensed since the current recovery (or the last restart) began, in order.
  const std::vector<map::SensedEdge>& sensed_sequence() const { return assembler_.sequence(); }
  const std::vector<EdgeAssembler::Span>& sensed_spans() const { return assembler_.spans(); }
  // The odometer reading last advanced to, and the travel direction along it (+1, -1; 0
  // before the robot has moved): the frame of sensed_spans().
  double odometer_in() const { return assembler_.odometer_in(); }
  int travel_direction() const { return assembler_.travel_direction(); }
  // Bayes: the share of the filter's belief at the robot in ring-local edge `edge` of `ring`,
  // travelling `dir`, a neighbour, or up to `ahead` edges further on (0 without a filter).
  double BeliefNear(int ring, int edge, int dir, int ahead = 0) const;

 private:
  void Rebuild(double odometer_in, const std::string& message);
  bool ExtendDeterministic(const std::vector<map::SensedEdge>& edges);
  void ExtendBayes(const std::vector<map::SensedEdge>& edges);
  // One hypothesis: the robot is past global edge `last` travelling `dir`.
  Hypothesis MakeHypothesis(int last, int dir, double past_in, double probability) const;
  // One hypothesis: `offset_in` into ring-local edge `edge` of ring `ring`.
  Hypothesis MakeHypothesisAt(int ring, int edge, int dir, double offset_in,
                              double probability) const;
  // Maintenance after localization; true if the estimate changed.
  bool Track(double odometer_in, const std::vector<map::SensedEdge>& edges, bool silence_changed);
  // Recovery from no knowledge; true if the estimate changed.
  bool Recover(double odometer_in, const std::vector<map::SensedEdge>& edges);
  void StartTracking(double odometer_in);
  void ResetRecovery();
  bool TrackWithFilter(double odometer_in, const std::vector<map::SensedEdge>& edges,
                       bool silence_changed);
  // The tracker's message for a pose the filter holds (never its own LOST).
  std::string TrackerNote() const;
  // The tracked pose as the estimate: LOCALIZED with the filter's `posterior` (calibrated
  // as the confidence).
  void PublishTracked(double posterior, const std::string& message);
  double Confidence(double posterior) const;
  // The edge the filter's place (g, dir) puts the robot in: the one after g, g sensed last.
  TrackedPose FilterPlace(const recovery::PoseBelief& b) const;
  // Whether the tracker has the robot in the edge the filter's place puts it in.
  bool TrackerAtFilterPlace(const recovery::PoseBelief& b) const;
  // Whether a place of the filter is the tracked pose slipped by a few edges.
  bool NearTrackedPose(const recovery::PoseBelief& b) const;
  // The share of the Bayes filter's belief that agrees with the tracked pose.
  double BeliefInTrackedPose() const;
  // Between edges: the belief in the place held at the last sensed edge, carried on by the
  // map edges the tracker has passed since (it dead-reckons past doors the filter has not
  // been given, missed or not yet decided).
  double BeliefSinceLastEdge() const;
  // A pose given up with the evidence against it: LOST once `lost_confirm_edges` further
  // edges keep the belief in it (moved on by the edges sensed) under lost_threshold and
  // have not raised it.
  void ConfirmLoss();
  // The pose is given up: LOST, and a new recovery starts from nothing.
  void Lose(const std::string& why);
  void LeaveLocalized(double odometer_in, Status status, const std::string& why);

  const map::Map& map_;
  LocalizerConfig config_;
  map::MatchIndex index_;
  map::SequenceMatcher matcher_;
  std::unique_ptr<recovery::BayesLocalizer> bayes_;
  EdgeAssembler assembler_;
  PoseEstimate estimate_;
  double posterior_ = 0.0;  // the best place's raw posterior behind estimate_.confidence
  PoseTracker tracker_;
  std::uint64_t restarts_ = 0;
  std::uint64_t losses_ = 0;
  std::uint64_t edges_total_ = 0;
  int recovery_edges_ = 0;  // edges weighed since the current recovery began
  double kidnap_per_edge_ = 0.0;  // the filter's kidnap share while a pose is held
  bool was_localized_ = false;
  std::optional<GivenUp> given_up_;
  TrackedPose held_at_edge_;   // the place held as the last sensed edge left it
  bool loss_pending_ = false;  // given_up_ is against the evidence, LOST not yet said
};

}  // namespace stickrep::localizer
