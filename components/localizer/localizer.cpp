#include "localizer/localizer.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "common/units.h"

namespace stickrep::localizer {

namespace {
// A place of the filter this many edges or fewer from the tracked one, in the same direction,
// is the tracked pose slipped (a reversal, a missed anchor), not another place.
constexpr int kNearEdges = 4;
// The silence since the last edge is weighed again each time it has grown by this much.
constexpr double kSilenceStepIn = 1.0;
}  // namespace

const char* ToString(Status s) {
  switch (s) {
    case Status::kRecovering: return "RECOVERING";
    case Status::kLocalized: return "LOCALIZED";
    case Status::kLost: return "LOST";
  }
  return "?";
}

Localizer::Localizer(const map::Map& map, LocalizerConfig config)
    : map_(map),
      config_(config),
      index_(map),
      matcher_(index_, config.tolerance),
      assembler_(config.assembler),
      tracker_(map, config.tracker) {
  if (config_.method == MatchMethod::kBayes) {
    recovery::BayesModel model = config_.bayes;
    kidnap_per_edge_ = model.settings.kidnap_per_edge;
    model.settings.kidnap_per_edge = 0.0;  // from the first pose on (StartTracking)
    bayes_ = std::make_unique<recovery::BayesLocalizer>(index_, model);
  }
  estimate_.message = "waiting for the first edge";
}

bool Localizer::Advance(double odometer_in, double heading_rad) {
  const std::vector<map::SensedEdge> edges = assembler_.Advance(odometer_in, heading_rad);
  if (assembler_.TakeReversal()) {
    if (tracker_.status() == TrackStatus::kTracking) {
      // The same place, travelled the other way: the edge is entered from its other end.
      if (bayes_) {
        bayes_->Reverse(assembler_.reversal_travel_in());
        assembler_.Restart();
      }
      TrackedPose p = tracker_.pose();
      const double metric = map_.ring(p.ring).edges[p.edge].metric_in;
      p.dir = -p.dir;
      p.offset_in = std::max(0.0, metric - p.offset_in);
      tracker_.Start(p, odometer_in, assembler_.travel_direction());
      estimate_.hypotheses = {MakeHypothesisAt(p.ring, p.edge, p.dir, p.offset_in, 1.0)};
      estimate_.message = "travel reversed: the pose is kept, travelling the other way";
      return true;
    }
    if (bayes_ && bayes_->edges() > 0) {
      // Recovering with the filter: its belief is carried over to the way back (a hallway
      // end no longer throws the edges sensed so far away).
      bayes_->Reverse(assembler_.reversal_travel_in());
      assembler_.Restart();
      loss_pending_ = false;  // the pose given up was the other way: RECOVERING it stays
      Rebuild(odometer_in, "travel reversed: the evidence is kept, travelling the other way");
      return true;
    }
    // Recovering: the sequence so far was sensed the other way round; start a new one.
    ResetRecovery();
    restarts_++;
    Rebuild(odometer_in, "travel reversed: a new sequence");
    return true;
  }
  // With the filter, the pose stays until the filter gives it up (the tracker may have lost
  // its anchor meanwhile); without it, while the tracker keeps it.
  const bool localized = bayes_ ? estimate_.status == Status::kLocalized
                                : tracker_.status() == TrackStatus::kTracking;
  // While recovering, what has not been sensed since the last edge is evidence too: a door
  // or corner the best place expects by now that did not come keeps it from being declared
  // (confirm_silent_in). While localized it tests the held pose when silence_tests_pose is
  // set (else the filter's belief is weighed by edges alone).
  bool silence_changed = false;
  if (bayes_ && (!localized || config_.silence_tests_pose) && edges.empty() &&
      bayes_->edges() > 0) {
    const std::optional<double> silent = assembler_.silent_in();
    if (silent && std::abs(*silent - bayes_->silent_in()) >= kSilenceStepIn) {
      bayes_->SetSilence(*silent);
      silence_changed = true;
    }
  }
  if (localized) return Track(odometer_in, edges, silence_changed);
  const bool changed = Recover(odometer_in, edges);
  if (estimate_.status == Status::kLocalized) StartTracking(odometer_in);
  return changed;
}

void Localizer::StartTracking(double odometer_in) {
  // While a pose is held the filter allows for a kidnap before every edge.
  if (bayes_) bayes_->SetKidnapShare(kidnap_per_edge_);
  const Hypothesis& h = estimate_.hypotheses.front();
  tracker_.Start(TrackedPose{h.ring, h.edge, h.dir, h.offset_in}, odometer_in,
                 assembler_.travel_direction());
  // A pose declared on the silence past the last edge starts the tracker edges beyond the
  // place the filter holds at that edge: the silence is weighed from the filter's place.
  const bool filter_place = bayes_ && bayes_->edges() > 0 && bayes_->best().edge >= 0;
  held_at_edge_ = filter_place ? FilterPlace(bayes_->best()) : tracker_.pose();
}

void Localizer::ResetRecovery() {
  loss_pending_ = false;
  matcher_.Reset();
  if (bayes_) {
    bayes_->Reset();
    bayes_->SetKidnapShare(0.0);
  }
  assembler_.Restart();
  recovery_edges_ = 0;
}

bool Localizer::Track(double odometer_in, const std::vector<map::SensedEdge>& edges,
                      bool silence_changed) {
  edges_total_ += edges.size();
  tracker_.Advance(odometer_in);
  if (!edges.empty() && assembler_.last_edge_end_in()) {
    tracker_.OnEdges(edges, *assembler_.last_edge_end_in());
  }
  if (bayes_) return TrackWithFilter(odometer_in, edges, silence_changed);
  if (tracker_.status() == TrackStatus::kLost) {
    // The anticipated edges stopped coming (kidnapped, or the odometry drifted beyond
    // repair): recover from scratch.
    Lose("pose lost (" + tracker_.message() + "): recovering again");
    return true;
  }
  PublishTracked(1.0, tracker_.message());
  return !edges.empty();
}

// Integrity: the filter weighs every edge as in recovery, the tracked place and the
// alternatives alike, and it decides which place the robot is at. The tracker places the
// robot along that edge by the odometer between edges. The pose stays LOCALIZED while the
// filter's belief in the tracked place holds keep_threshold; a place the filter is as sure of
// as a recovery needs takes over; otherwise the pose is given up: LOST when the belief in it
// has fallen under lost_threshold (the evidence is against it), RECOVERING when it is merely
// no longer sure. The filter's belief is kept either way: it goes on from there. A silence
// (silence_tests_pose) can only give the pose up, to RECOVERING.
bool Localizer::TrackWithFilter(double odometer_in, const std::vector<map::SensedEdge>& edges,
                                bool silence_changed) {
  if (edges.empty() && !silence_changed) {
    PublishTracked(posterior_, TrackerNote());
    return false;
  }
  if (!edges.empty()) ExtendBayes(edges);
  const double tracked = edges.empty() ? BeliefSinceLastEdge() : BeliefInTrackedPose();
  const recovery::PoseBelief& best = bayes_->best();
  const bool near = NearTrackedPose(best);
  const bool holds =
      (tracked >= config_.keep_threshold || near) && best.probability >= config_.keep_threshold;
  if (edges.empty() && holds) {
    PublishTracked(posterior_, TrackerNote());
    return false;
  }
  if (holds) {
    // The place holds. The tracker dead-reckons between edges (through a corner's turn, or
    // after a reversal, it can slip an edge or lose its anchor): it is put where the filter
    // places the robot after this edge.
    std::string message = TrackerNote();
    if (tracker_.status() != TrackStatus::kTracking || !TrackerAtFilterPlace(best)) {
      Rebuild(odometer_in, estimate_.message);
      StartTracking(odometer_in);
      message = "re-anchored on the sensed edges: " + tracker_.message();
    }
    PublishTracked(std::max(tracked, best.probability), message);
    held_at_edge_ = tracker_.pose();
  } else if (!edges.empty() && best.probability >= config_.bayes.settings.threshold) {
    // The filter is as sure of another place as a recovery needs to be: the pose moves there.
    Rebuild(odometer_in, estimate_.message);
    StartTracking(odometer_in);
    PublishTracked(best.probability, "the sensed edges place the robot elsewhere: " +
                                         tracker_.message());
  } else {
    // Against the pose: LOST at once, or once the next edges are against it too (a run of
    // misreads the model rates apart can sink a right pose for an edge; a kidnap keeps it
    // sunk).
    const bool against = tracked < config_.lost_threshold;
    const bool lost = against && config_.lost_confirm_edges == 0 && !edges.empty();
    const TrackedPose p = tracker_.pose();
    given_up_ =
        GivenUp{p.ring,      p.edge, p.dir, tracked, lost, (given_up_ ? given_up_->serial : 0) + 1,
                std::nullopt};
    LeaveLocalized(
        odometer_in, lost ? Status::kLost : Status::kRecovering,
        fmt::format(
            "{} the pose (belief {:.3f}): recovering from the filter's belief{}",
            edges.empty()
                ? fmt::format("the silence {:.0f} in past the last edge {}", bayes_->silent_in(),
                              against ? "is against" : "no longer confirms")
                : fmt::format("the sensed edges {}", against ? "are against" : "no longer confirm"),
            tracked, against && !lost ? "; LOST if the next edges are against it too" : ""));
    loss_pending_ = against && !lost;
  }
  return true;
}

void Localizer::ConfirmLoss() {
  if (!loss_pending_ || !given_up_) return;
  if (estimate_.status == Status::kLocalized) {
    loss_pending_ = false;  // a place is held again: what became of the old one is moot
    return;
  }
  // Since the pose was given up, recovery_edges_ edges were sensed: the robot, had it been
  // there, is up to that many edges on (fewer where the filter takes some for false doors).
  const double belief =
      BeliefNear(given_up_->ring, given_up_->edge, given_up_->dir, recovery_edges_);
  given_up_->belief_on = belief;
  if (belief >= config_.lost_threshold) {
    loss_pending_ = false;
    estimate_.message += fmt::format(
        "; the pose given up is not against the evidence now "
        "(belief {:.4f}): no LOST",
        belief);
    return;
  }
  if (recovery_edges_ < config_.lost_confirm_edges) return;
  loss_pending_ = false;
  if (belief > given_up_->belief) {
    // The edges since were for the place, not against it: what sank it was a run of
    // misreads (the same doors missed pass after pass), or a kidnap whose next edges the
    // old place has too. LOST needs the evidence against the place before and after.
    estimate_.message += fmt::format(
        "; the edges since the pose was given up are for it (belief {:.2g}, up from {:.2g}): "
        "no LOST",
        belief, given_up_->belief);
    return;
  }
  losses_++;
  given_up_->lost = true;
  estimate_.status = Status::kLost;
  estimate_.message += fmt::format(
      "; the pose given up is still against the evidence {} edges "
      "on (belief {:.2g}): LOST",
      recovery_edges_, belief);
}

// The pose is given up but the filter's belief kept: the recovery goes on from it.
void Localizer::LeaveLocalized(double odometer_in, Status status, const std::string& why) {
  if (status == Status::kLost) losses_++;
  tracker_.Stop(why);
  bayes_->SetKidnapShare(0.0);
  recovery_edges_ = 0;
  was_localized_ = false;
  Rebuild(odometer_in, why);
  estimate_.status = status;
}

double Localizer::Confidence(double posterior) const {
  return bayes_ ? config_.calibration.Calibrated(posterior) : posterior;
}

std::string Localizer::TrackerNote() const {
  // Under the filter the tracker's own LOST (its anticipated doors stopped coming) only
  // loses its anchor along the edge: the filter decides at the next edge whether the place
  // holds, and the status stays LOCALIZED until then. The note must not say LOST.
  if (tracker_.status() != TrackStatus::kLost) return tracker_.message();
  return fmt::format(
      "{} anticipated edges in a row not seen: the place is held until the filter weighs the "
      "next edge",
      tracker_.consecutive_misses());
}

void Localizer::PublishTracked(double posterior, const std::string& message) {
  const TrackedPose p = tracker_.pose();
  estimate_.hypotheses = {MakeHypothesisAt(p.ring, p.edge, p.dir, p.offset_in, posterior)};
  estimate_.candidates = 1;
  posterior_ = posterior;
  estimate_.confidence = Confidence(posterior);
  estimate_.status = Status::kLocalized;
  estimate_.message = message;
}

TrackedPose Localizer::FilterPlace(const recovery::PoseBelief& b) const {
  const int next = index_.Step(b.edge, b.dir);
  const int g = next >= 0 ? next : b.edge;
  const int ring = index_.RingOf(g);
  return TrackedPose{ring, g - index_.RingOffset(ring), b.dir, 0.0};
}

bool Localizer::TrackerAtFilterPlace(const recovery::PoseBelief& b) const {
  const TrackedPose f = FilterPlace(b);
  const TrackedPose p = tracker_.pose();
  return p.dir == f.dir && p.ring == f.ring && p.edge == f.edge;
}

bool Localizer::NearTrackedPose(const recovery::PoseBelief& b) const {
  if (b.edge < 0) return false;
  const TrackedPose p = tracker_.pose();
  if (b.dir != p.dir || index_.RingOf(b.edge) != p.ring) return false;
  const int n = index_.RingSize(p.ring);
  int d = std::abs(b.edge - index_.RingOffset(p.ring) - p.edge);
  if (index_.RingClosed(p.ring)) d = std::min(d, n - d);
  return d <= kNearEdges;
}

double Localizer::BeliefInTrackedPose() const {
  const TrackedPose p = tracker_.pose();
  return BeliefNear(p.ring, p.edge, p.dir);
}

double Localizer::BeliefSinceLastEdge() const {
  const TrackedPose p = tracker_.pose();
  const TrackedPose& a = held_at_edge_;
  if (p.ring != a.ring || p.dir != a.dir) return BeliefInTrackedPose();
  const int n = index_.RingSize(a.ring);
  int passed = a.dir * (p.edge - a.edge);
  if (index_.RingClosed(a.ring)) passed = (passed % n + n) % n;
  if (passed < 0 || passed > n / 2) passed = 0;  // slipped back: the place held itself
  return BeliefNear(a.ring, a.edge, a.dir, std::min(passed, kNearEdges));
}

double Localizer::BeliefNear(int ring, int edge, int dir, int ahead) const {
  if (!bayes_) return 0.0;
  const int ring_size = index_.RingSize(ring);
  double belief = 0.0;
  // Filter state (g, dir): g sensed last, the robot in the edge after it (k = 1). A
  // neighbour counts too (k = 0, 2; k = -1: the tracker is an edge behind): the pose may be
  // anchored on an edge whose end the filter has not been given yet. `ahead` edges further
  // on count as well.
  for (int k = -1 - std::max(0, ahead); k <= 2; ++k) {
    int e = edge - dir * k;
    if (index_.RingClosed(ring)) e = (e % ring_size + ring_size) % ring_size;
    if (e < 0 || e >= ring_size) continue;
    belief += bayes_->PoseProbability(index_.RingOffset(ring) + e, dir);
  }
  return belief;
}

void Localizer::Lose(const std::string& why) {
  losses_++;
  tracker_.Stop(why);
  ResetRecovery();
  estimate_ = PoseEstimate{};
  posterior_ = 0.0;
  estimate_.status = Status::kLost;
  estimate_.message = why;
  was_localized_ = false;
}

bool Localizer::Recover(double odometer_in, const std::vector<map::SensedEdge>& edges) {
  if (edges.empty()) {
    if (estimate_.hypotheses.empty()) return false;
    // The silence since the last edge may confirm the best place (confirm_silent_in).
    const bool declared = bayes_ && bayes_->status() == recovery::RecoveryStatus::kLocalized;
    Rebuild(odometer_in, declared ? fmt::format("best place has posterior {:.4f} with {:.0f} in "
                                                "sensed past the last edge: pose recovered",
                                                bayes_->best().probability, bayes_->silent_in())
                                  : estimate_.message);
    return declared;
  }
  edges_total_ += edges.size();
  if (bayes_) {
    ExtendBayes(edges);
    const double p = bayes_->best().probability;
    Rebuild(odometer_in, bayes_->status() == recovery::RecoveryStatus::kLocalized
                             ? fmt::format("best place has posterior {:.4f}: pose recovered", p)
                             : fmt::format("best place has posterior {:.4f}", p));
    ConfirmLoss();
    return true;
  }
  if (!ExtendDeterministic(edges)) return true;
  const std::size_t n = matcher_.candidates().size();
  const std::string message = n == 1 ? "one place fits: pose recovered"
                                     : std::to_string(n) + " places fit";
  Rebuild(odometer_in, message);
  return true;
}

bool Localizer::ExtendDeterministic(const std::vector<map::SensedEdge>& edges) {
  for (const map::SensedEdge& e : edges) {
    if (matcher_.Extend(e) == 0) {
      // A sensing error: nothing on the map fits. Discard the sequence and start again.
      restarts_++;
      matcher_.Reset();
      assembler_.Restart();
      estimate_ = PoseEstimate{};
      posterior_ = 0.0;
      estimate_.status = was_localized_ ? Status::kLost : Status::kRecovering;
      estimate_.message = "no place fits the sensed edges: sequence discarded, starting again";
      was_localized_ = false;
      return false;
    }
  }
  return true;
}

void Localizer::ExtendBayes(const std::vector<map::SensedEdge>& edges) {
  if (config_.direction_from_travel) bayes_->SetTravelDirection(-assembler_.travel_direction());
  for (const map::SensedEdge& e : edges) bayes_->Add(e);
  recovery_edges_ += static_cast<int>(edges.size());
}

void Localizer::Rebuild(double odometer_in, const std::string& message) {
  // How far the robot is past the last matched edge.
  double past_in = 0.0;
  if (assembler_.last_edge_end_in() && assembler_.travel_direction() != 0) {
    past_in = std::max(0.0, assembler_.travel_direction() *
                                (odometer_in - *assembler_.last_edge_end_in()));
  }
  estimate_.hypotheses.clear();
  estimate_.message = message;
  if (bayes_) {
    const auto top = bayes_->Top(config_.max_hypotheses);
    estimate_.candidates = 0;
    for (const recovery::PoseBelief& b : top) {
      if (b.edge < 0 || b.probability <= 0.0) continue;
      estimate_.hypotheses.push_back(MakeHypothesis(b.edge, b.dir, past_in, b.probability));
      estimate_.candidates += b.probability > 1e-3;
    }
    estimate_.edges_sensed = recovery_edges_;
    posterior_ = top.empty() ? 0.0 : top.front().probability;
    estimate_.confidence = Confidence(posterior_);
    const bool localized = bayes_->status() == recovery::RecoveryStatus::kLocalized;
    estimate_.status = localized ? Status::kLocalized : Status::kRecovering;
    if (localized) was_localized_ = true;
    return;
  }
  const auto& cands = matcher_.candidates();
  estimate_.candidates = cands.size();
  estimate_.edges_sensed = matcher_.length();
  estimate_.status = cands.size() == 1 ? Status::kLocalized : Status::kRecovering;
  if (cands.size() == 1) was_localized_ = true;
  posterior_ = cands.empty() ? 0.0 : 1.0 / static_cast<double>(cands.size());
  estimate_.confidence = posterior_;
  for (std::size_t i = 0; i < cands.size() && static_cast<int>(i) < config_.max_hypotheses; ++i) {
    estimate_.hypotheses.push_back(
        MakeHypothesis(cands[i].last, cands[i].dir, past_in, estimate_.confidence));
  }
}

Hypothesis Localizer::MakeHypothesis(int last, int dir, double past_in,
                                     double probability) const {
  // The newest sensed edge has left the view: the robot is in the next edge, or further on
  // by the odometer (a door it has passed may still be in view, not yet emitted).
  const int next = index_.Step(last, dir);
  int g = next >= 0 ? next : last;
  for (int i = 0; i < kNearEdges && past_in > index_.metric(g); ++i) {
    const int ahead = index_.Step(g, dir);
    if (ahead < 0 || index_.open_end(ahead)) break;
    past_in -= index_.metric(g);
    g = ahead;
  }
  const int ring = index_.RingOf(g);
  return MakeHypothesisAt(ring, g - index_.RingOffset(ring), dir, past_in, probability);
}

Hypothesis Localizer::MakeHypothesisAt(int ring_index, int edge, int dir, double offset_in,
                                       double probability) const {
  return PlaceOnMap(map_, ring_index, edge, dir, offset_in, probability);
}

Hypothesis PlaceOnMap(const map::Map& map, int ring_index, int edge, int dir, double offset_in,
                      double probability) {
  Hypothesis h;
  h.ring = ring_index;
  h.edge = edge;
  h.dir = dir;
  const map::Ring& ring = map.ring(h.ring);
  h.offset_in = std::clamp(offset_in, 0.0, ring.edges[h.edge].metric_in);
  // Node e starts edge e in ring order and carries that edge's heading (gamma).
  const map::Node& start = ring.nodes[h.edge];
  const map::Node& end = ring.nodes[(h.edge + 1) % ring.NodeCount()];
  const double ring_heading = DegToRad(start.gamma_deg);
  const map::Node& from = h.dir > 0 ? start : end;
  h.heading_rad = std::remainder(ring_heading + (h.dir > 0 ? 0.0 : kPi), 2.0 * kPi);
  h.x_in = from.x_in + h.offset_in * std::cos(h.heading_rad);
  h.y_in = from.y_in + h.offset_in * std::sin(h.heading_rad);
  h.probability = probability;
  return h;
}

Hypothesis OnOriginalMap(const map::HallwayView& view, const Hypothesis& h) {
  const map::HallwayView::Place p = view.ToOriginal(h.ring, h.edge, h.dir, h.offset_in);
  return PlaceOnMap(view.original(), h.ring, p.edge, h.dir, p.offset_in, h.probability);
}

}  // namespace stickrep::localizer
