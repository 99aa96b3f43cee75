#pragma once

// The matcher used by the recovery strategies: map::SequenceMatcher, plus the relaxation of
// door widths that the mis-sized-door heuristic needs (§6.5, §6.6.3). With door relaxation
// off it is exactly map::SequenceMatcher (which it wraps); with it on, a sensed door also
// matches a map door of another class whose width is within the relaxation of the sensed
// width — SequenceMatcher compares door classes only, so that case has its own loop here,
// which reuses SequenceMatcher::Matches for the metric and the angle.

#include <cstddef>
#include <vector>

#include "stickrep/sequence_matcher.h"

namespace stickrep::recovery {

class RelaxedMatcher {
 public:
  RelaxedMatcher(const map::MatchIndex& index, map::MatchTolerance base);

  // Figure 6.4's relaxation: `wall_rel` is added to the base relative metric tolerance of
  // walls and other metric edges; `door_rel` lets a sensed door match a map door whose
  // class width w satisfies |w - sensed width| <= door_rel * w. Takes effect for later
  // Extend() calls; call MatchAll() to re-match a sequence.
  void SetRelaxation(double wall_rel, double door_rel);
  double wall_relaxation() const { return wall_rel_; }
  double door_relaxation() const { return door_rel_; }

  void Reset();
  std::size_t Extend(const map::SensedEdge& edge);
  // Reset() and Extend() each edge; stops at zero candidates.
  std::size_t MatchAll(const std::vector<map::SensedEdge>& sequence);

  const std::vector<map::Candidate>& candidates() const {
    return door_rel_ > 0.0 ? candidates_ : plain_.candidates();
  }
  int length() const { return door_rel_ > 0.0 ? length_ : plain_.length(); }
  const map::MatchIndex& index() const { return index_; }

 private:
  // Whether map edge g in direction dir accepts the sensed door `edge` under door relaxation.
  bool AcceptsDoor(int g, int dir, const map::SensedEdge& edge, bool first) const;

  const map::MatchIndex& index_;
  map::MatchTolerance base_;
  map::SequenceMatcher plain_;
  double wall_rel_ = 0.0;
  double door_rel_ = 0.0;
  std::vector<map::Candidate> candidates_;
  int length_ = 0;
};

}  // namespace stickrep::recovery
