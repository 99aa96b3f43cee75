#include "recovery/relaxed_matcher.h"

#include <cmath>

namespace stickrep::recovery {

namespace {

double CodeWidthIn(map::SymbolCode code) {
  return map::DoorClassWidthIn(static_cast<map::DoorClass>(code - 1));
}

}  // namespace

RelaxedMatcher::RelaxedMatcher(const map::MatchIndex& index, map::MatchTolerance base)
    : index_(index), base_(base), plain_(index, base) {
  candidates_.reserve(2 * static_cast<std::size_t>(index.EdgeCount()));
}

void RelaxedMatcher::SetRelaxation(double wall_rel, double door_rel) {
  wall_rel_ = wall_rel;
  door_rel_ = door_rel;
  map::MatchTolerance t = base_;
  t.metric_rel += wall_rel;
  plain_.set_tolerance(t);
}

void RelaxedMatcher::Reset() {
  plain_.Reset();
  candidates_.clear();
  length_ = 0;
}

bool RelaxedMatcher::AcceptsDoor(int g, int dir, const map::SensedEdge& edge, bool first) const {
  const map::SymbolCode code = index_.code(g);
  if (!map::IsDoorCode(code)) return false;
  if (code != edge.code) {
    const double sensed = edge.metric_in > 0.0 ? edge.metric_in : CodeWidthIn(edge.code);
    const double w = CodeWidthIn(code);
    if (std::abs(w - sensed) > door_rel_ * w + 1e-9) return false;
  }
  // The class is accepted; the angle is checked as for an exact door.
  map::SensedEdge as_map = edge;
  as_map.code = code;
  return plain_.Matches(g, dir, as_map, first);
}

std::size_t RelaxedMatcher::Extend(const map::SensedEdge& edge) {
  if (door_rel_ <= 0.0) return plain_.Extend(edge);
  const bool door = map::IsDoorCode(edge.code);
  if (length_ == 0) {
    if (door) {
      for (int k = 0; k < map::kDoorClassCount; ++k) {
        for (const std::int32_t g :
             index_.EdgesWithCode(map::DoorCode(static_cast<map::DoorClass>(k)))) {
          if (!AcceptsDoor(g, +1, edge, /*first=*/true)) continue;
          candidates_.push_back({g, g, +1});
          candidates_.push_back({g, g, -1});
        }
      }
    } else {
      for (const std::int32_t g : index_.EdgesWithCode(edge.code)) {
        if (!plain_.Matches(g, +1, edge, /*first=*/true)) continue;
        candidates_.push_back({g, g, +1});
        candidates_.push_back({g, g, -1});
      }
    }
  } else {
    std::size_t kept = 0;
    for (std::size_t i = 0; i < candidates_.size(); ++i) {
      map::Candidate c = candidates_[i];
      const int next = index_.Step(c.last, c.dir);
      if (next < 0) continue;
      const bool ok =
          door ? AcceptsDoor(next, c.dir, edge, false) : plain_.Matches(next, c.dir, edge, false);
      if (!ok) continue;
      c.last = next;
      candidates_[kept++] = c;
    }
    candidates_.resize(kept);
  }
  ++length_;
  return candidates_.size();
}

std::size_t RelaxedMatcher::MatchAll(const std::vector<map::SensedEdge>& sequence) {
  Reset();
  std::size_t n = 0;
  for (const map::SensedEdge& e : sequence) {
    n = Extend(e);
    if (n == 0) break;
  }
  return n;
}

}  // namespace stickrep::recovery
