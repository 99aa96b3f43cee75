#pragma once

// The matching core (§6.1, §6.5): a sensed sequence of edges is matched, as a string with
// metric tolerance, against every position of every ring in both directions of travel.
// Candidates that survive one sensed edge are extended by the next, so adding an edge costs
// one comparison per surviving candidate. The ambiguity analysis (Figure 6.1) and the
// simulation study are both built on this.

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "stickrep/map.h"

namespace stickrep::map {

// What the matcher compares an edge by: its type, and for doors their class.
// 0 = wall, 1..6 = door classes 30, 32, 36, 40, 30/30, 36/36, then the other edge types.
using SymbolCode = std::uint8_t;
inline constexpr SymbolCode kWallCode = 0;
inline constexpr SymbolCode kElevatorCode = 7;
inline constexpr SymbolCode kStairwellCode = 8;
inline constexpr SymbolCode kCornerCode = 9;
inline constexpr SymbolCode kPatternCode = 10;
inline constexpr int kSymbolCodeCount = 11;

SymbolCode CodeOf(const Edge& edge);
inline SymbolCode DoorCode(DoorClass c) { return static_cast<SymbolCode>(1 + static_cast<int>(c)); }
inline bool IsDoorCode(SymbolCode code) { return code >= 1 && code <= 6; }
// Doors are matched by class alone (their metric is the class width); every other edge
// type is matched by its metric as well.
inline bool CodeHasMetric(SymbolCode code) { return !IsDoorCode(code); }
// "wall", "door36", "door30/30", "elevator", ...
const char* SymbolName(SymbolCode code);

// One edge as the robot sensed it.
struct SensedEdge {
  SymbolCode code = kWallCode;
  double metric_in = 0.0;  // measured length; ignored for doors
  // Adjacency angle at the node between the previous sensed edge and this one; NaN when it
  // was not sensed (and always ignored for the first edge of a sequence).
  double angle_deg = std::numeric_limits<double>::quiet_NaN();
  // The robot started inside this edge and saw only part of it: the metric is a lower bound.
  bool metric_is_lower_bound = false;
  // Doors: the leaf's mark as the camera read it (Table 6.8's supplemental marks); kUnknown
  // when not read, and always for walls and corners.
  DoorMark mark = DoorMark::kUnknown;
};

// One sensed edge in words, for logs and traces: "door36", "wall:46", "<270> wall:130",
// "door36[poster]" (a door whose mark was read).
std::string Describe(const SensedEdge& edge);
// A sequence of them, space-separated.
std::string Describe(const std::vector<SensedEdge>& edges);

// How far a sensed value may be from the map and still match. With all zero the match is
// exact, which is what "no sensing error" means (§6.4.1).
struct MatchTolerance {
  double metric_rel = 0.0;     // fraction of the map metric: 0.1, 0.2 in Figure 6.4
  double metric_abs_in = 0.0;  // plus this many inches
  double angle_deg = 0.0;      // angle allowance; negative: angles are not compared
};

// The map flattened for matching: every ring's edges stored contiguously (ring after ring)
// as small arrays of codes, metrics and end angles, plus the list of edges per code so that
// the first sensed edge only visits edges of its own kind. Built once per map; read-only.
class MatchIndex {
 public:
  explicit MatchIndex(const Map& map);

  int EdgeCount() const { return static_cast<int>(code_.size()); }
  int RingCount() const { return static_cast<int>(ring_offset_.size()); }
  int RingOffset(int r) const { return ring_offset_[r]; }
  int RingSize(int r) const { return ring_size_[r]; }
  bool RingClosed(int r) const { return ring_closed_[r] != 0; }
  int RingOf(int g) const { return ring_of_[g]; }
  int MaxRingSize() const { return max_ring_size_; }

  SymbolCode code(int g) const { return code_[g]; }
  // The mark on door g's leaf (DoorMarkOfPattern of its pattern: kUnknown where the map
  // does not say); kUnknown for non-doors.
  DoorMark mark(int g) const { return static_cast<DoorMark>(mark_[g]); }
  double metric(int g) const { return metric_[g]; }
  // Angle of the node at the start / end of edge g in ring order.
  double angle_start(int g) const { return angle_start_[g]; }
  double angle_end(int g) const { return angle_end_[g]; }
  // Whether edge g is a corridor's open end (map::IsOpenEnd): travelling into it the robot
  // leaves the ring. Matched as wall.
  bool open_end(int g) const { return open_end_[g] != 0; }
  // Whether edge g is a door in a row or a short wall between two doors (map::InDoorRow).
  bool in_row(int g) const { return in_row_[g] != 0; }
  // Global indices of all edges with this code, in ring order.
  const std::vector<std::int32_t>& EdgesWithCode(SymbolCode code) const { return by_code_[code]; }

  // The global index of the edge after g in direction dir (+1 ring order, -1 against it);
  // -1 past the end of an open ring.
  int Step(int g, int dir) const {
    const int r = ring_of_[g];
    const int off = ring_offset_[r];
    const int n = ring_size_[r];
    int local = g - off + dir;
    if (local < 0 || local >= n) {
      if (!ring_closed_[r]) return -1;
      local = local < 0 ? n - 1 : 0;
    }
    return off + local;
  }
  // Global index of edge i of ring r (0 <= i < size).
  int Global(int r, int i) const { return ring_offset_[r] + i; }

 private:
  std::vector<SymbolCode> code_;
  std::vector<double> metric_;
  std::vector<std::uint8_t> mark_;
  std::vector<double> angle_start_;
  std::vector<double> angle_end_;
  std::vector<std::uint8_t> open_end_;
  std::vector<std::uint8_t> in_row_;
  std::vector<std::int32_t> ring_of_;
  std::vector<std::int32_t> ring_offset_;
  std::vector<std::int32_t> ring_size_;
  std::vector<std::uint8_t> ring_closed_;
  std::vector<std::int32_t> by_code_[kSymbolCodeCount];
  int max_ring_size_ = 0;
};

// One place the sensed sequence could have come from: the first sensed edge is `start`
// (global index) travelled in direction `dir`; `last` is the edge matched to the newest
// sensed edge.
struct Candidate {
  std::int32_t start = 0;
  std::int32_t last = 0;
  std::int8_t dir = +1;
};

// Incremental matcher of one sensed sequence. Reset(), then Extend() once per sensed edge;
// candidates() are the places still consistent with everything sensed so far.
class SequenceMatcher {
 public:
  SequenceMatcher(const MatchIndex& index, MatchTolerance tolerance = {});

  void Reset() {
    candidates_.clear();
    length_ = 0;
  }
  // Adds one sensed edge; returns the number of surviving candidates (0: sensing error,
  // 1: pose found, more: keep travelling).
  std::size_t Extend(const SensedEdge& edge);
  // Reset() and Extend() with each edge of `sequence`; stops early at zero candidates.
  std::size_t MatchAll(const std::vector<SensedEdge>& sequence);

  const std::vector<Candidate>& candidates() const { return candidates_; }
  int length() const { return length_; }
  const MatchTolerance& tolerance() const { return tolerance_; }
  // Changes the tolerance for later Extend() calls (metric relaxation re-matches with
  // MatchAll after changing it).
  void set_tolerance(const MatchTolerance& tolerance) { tolerance_ = tolerance; }

  // Whether map edge g, reached in direction dir, is consistent with `edge`. `first` skips
  // the angle (no node has been crossed yet).
  bool Matches(int g, int dir, const SensedEdge& edge, bool first) const {
    if (index_.code(g) != edge.code) return false;
    if (CodeHasMetric(edge.code)) {
      const double m = index_.metric(g);
      const double allow = std::max(tolerance_.metric_abs_in, tolerance_.metric_rel * m) + 1e-9;
      if (edge.metric_is_lower_bound) {
        if (m < edge.metric_in - allow) return false;
      } else if (std::abs(m - edge.metric_in) > allow) {
        return false;
      }
    }
    if (!first && tolerance_.angle_deg >= 0.0 && !std::isnan(edge.angle_deg)) {
      const double a = dir > 0 ? index_.angle_start(g) : index_.angle_end(g);
      if (std::abs(a - edge.angle_deg) > tolerance_.angle_deg + 1e-9) return false;
    }
    return true;
  }

 private:
  const MatchIndex& index_;
  MatchTolerance tolerance_;
  std::vector<Candidate> candidates_;
  int length_ = 0;
};

// What the robot senses with no error when it travels from `start` for `count` edges: the
// exact symbols of the map edges, with the angles at the nodes crossed. Stops early at the
// end of an open ring.
std::vector<SensedEdge> ExactSequence(const MatchIndex& index, int start, int dir, int count);

}  // namespace stickrep::map
