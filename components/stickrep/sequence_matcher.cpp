#include "stickrep/sequence_matcher.h"

#include <algorithm>

namespace stickrep::map {

SymbolCode CodeOf(const Edge& edge) {
  switch (edge.type) {
    case EdgeType::kDoorway:
      return DoorCode(*edge.door_class);
    case EdgeType::kHallway:
    case EdgeType::kOpening:  // passed like wall: no door, no corner (HallwayView merges it)
      return kWallCode;
    case EdgeType::kElevator:
      return kElevatorCode;
    case EdgeType::kStairwell:
      return kStairwellCode;
    case EdgeType::kCorner:
      return kCornerCode;
    case EdgeType::kPattern:
      return kPatternCode;
  }
  return kWallCode;
}

const char* SymbolName(SymbolCode code) {
  static constexpr const char* kNames[kSymbolCodeCount] = {
      "wall",      "door30",   "door32",    "door36", "door40", "door30/30",
      "door36/36", "elevator", "stairwell", "corner", "pattern"};
  return code < kSymbolCodeCount ? kNames[code] : "?";
}

MatchIndex::MatchIndex(const Map& map) {
  code_.reserve(map.EdgeCount());
  for (int r = 0; r < map.RingCount(); ++r) {
    const Ring& ring = map.ring(r);
    ring_offset_.push_back(static_cast<std::int32_t>(code_.size()));
    ring_size_.push_back(ring.EdgeCount());
    ring_closed_.push_back(ring.closed ? 1 : 0);
    max_ring_size_ = std::max(max_ring_size_, ring.EdgeCount());
    for (int i = 0; i < ring.EdgeCount(); ++i) {
      const Edge& e = ring.edges[i];
      const int g = static_cast<int>(code_.size());
      code_.push_back(CodeOf(e));
      metric_.push_back(e.metric_in);
      mark_.push_back(static_cast<std::uint8_t>(
          IsDoorCode(code_.back()) ? DoorMarkOfPattern(e.pattern) : DoorMark::kUnknown));
      angle_start_.push_back(ring.nodes[i].angle_deg);
      angle_end_.push_back(ring.nodes[(i + 1) % ring.NodeCount()].angle_deg);
      open_end_.push_back(IsOpenEnd(e, angle_start_.back(), angle_end_.back()) ? 1 : 0);
      in_row_.push_back(InDoorRow(ring, i) ? 1 : 0);
      ring_of_.push_back(r);
      by_code_[code_.back()].push_back(g);
    }
  }
}

SequenceMatcher::SequenceMatcher(const MatchIndex& index, MatchTolerance tolerance)
    : index_(index), tolerance_(tolerance) {
  candidates_.reserve(2 * static_cast<std::size_t>(index.EdgeCount()));
}

std::size_t SequenceMatcher::Extend(const SensedEdge& edge) {
  if (length_ == 0) {
    for (const std::int32_t g : index_.EdgesWithCode(edge.code)) {
      // The first edge has no node behind it, so both directions test the same thing.
      if (!Matches(g, +1, edge, /*first=*/true)) continue;
      candidates_.push_back({g, g, +1});
      candidates_.push_back({g, g, -1});
    }
  } else {
    std::size_t kept = 0;
    for (std::size_t i = 0; i < candidates_.size(); ++i) {
      Candidate c = candidates_[i];
      const int next = index_.Step(c.last, c.dir);
      if (next < 0 || !Matches(next, c.dir, edge, /*first=*/false)) continue;
      c.last = next;
      candidates_[kept++] = c;
    }
    candidates_.resize(kept);
  }
  ++length_;
  return candidates_.size();
}

std::size_t SequenceMatcher::MatchAll(const std::vector<SensedEdge>& sequence) {
  Reset();
  for (const SensedEdge& e : sequence) {
    if (Extend(e) == 0) break;
  }
  return candidates_.size();
}

std::vector<SensedEdge> ExactSequence(const MatchIndex& index, int start, int dir, int count) {
  std::vector<SensedEdge> out;
  int g = start;
  for (int k = 0; k < count && g >= 0; ++k) {
    SensedEdge e;
    e.code = index.code(g);
    e.metric_in = index.metric(g);
    if (k > 0) e.angle_deg = dir > 0 ? index.angle_start(g) : index.angle_end(g);
    out.push_back(e);
    g = index.Step(g, dir);
  }
  return out;
}

std::string Describe(const SensedEdge& e) {
  std::string s = SymbolName(e.code);
  if (CodeHasMetric(e.code)) s += ":" + std::to_string(static_cast<long>(std::lround(e.metric_in)));
  if (e.mark != DoorMark::kUnknown) s += std::string("[") + DoorMarkName(e.mark) + "]";
  if (std::isfinite(e.angle_deg) && std::abs(e.angle_deg - 180.0) > 1.0) {
    s = "<" + std::to_string(static_cast<long>(std::lround(e.angle_deg))) + "> " + s;
  }
  return s;
}

std::string Describe(const std::vector<SensedEdge>& edges) {
  std::string s;
  for (const SensedEdge& e : edges) s += (s.empty() ? "" : " ") + Describe(e);
  return s;
}

}  // namespace stickrep::map
