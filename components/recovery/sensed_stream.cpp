#include "recovery/sensed_stream.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/seeds.h"

namespace stickrep::recovery {

namespace {

double U01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

bool Coplanar(double angle_deg) { return std::abs(angle_deg - 180.0) < 1.0; }

}  // namespace

std::uint64_t RunSeed(std::uint64_t seed, std::uint64_t trial, std::uint64_t run) {
  return SplitMix64(SplitMix64(SplitMix64(seed) ^ trial) ^ run);
}

RunStart DrawStart(const map::MatchIndex& index, std::mt19937_64& rng,
                   const std::vector<int>& rings) {
  const auto drawn = [&](int g) {
    return rings.empty() || std::find(rings.begin(), rings.end(), index.RingOf(g)) != rings.end();
  };
  double total = 0;
  int last = -1;
  for (int g = 0; g < index.EdgeCount(); ++g) {
    if (!drawn(g)) continue;
    total += index.metric(g);
    last = g;
  }
  if (last < 0) throw std::invalid_argument("no edge to start beside on the rings given");
  double x = U01(rng) * total;
  RunStart s;
  s.edge = last;
  for (int g = 0; g < index.EdgeCount(); ++g) {
    if (!drawn(g)) continue;
    if (x < index.metric(g)) {
      s.edge = g;
      break;
    }
    x -= index.metric(g);
  }
  x = std::clamp(x, 0.0, index.metric(s.edge));
  s.dir = U01(rng) < 0.5 ? +1 : -1;
  s.offset_in = s.dir > 0 ? x : index.metric(s.edge) - x;
  return s;
}

SensedStream::SensedStream(const map::MatchIndex& index, const Confusion& confusion,
                           const SensingNoise& noise, const map::MatchTolerance& tolerance,
                           std::uint64_t seed, const std::vector<int>& start_rings)
    : index_(index), confusion_(confusion), noise_(noise), tolerance_(tolerance), rng_(seed) {
  start_ = DrawStart(index, rng_, start_rings);
  scale_error_ = noise_.wheel_scale_sigma_rel > 0 ? noise_.wheel_scale_sigma_rel * Gauss() : 0.0;
  next_edge_ = start_.edge;
  next_pos_ = -start_.offset_in;
}

double SensedStream::Gauss() {
  // Box-Muller; u1 in (0, 1].
  const double u1 = 1.0 - Uniform();
  const double u2 = Uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * 3.14159265358979323846 * u2);
}

map::DoorMark SensedStream::DrawMark(int truth, bool class_right) {
  if (!confusion_.marks) return map::DoorMark::kUnknown;
  if (truth < 0) return static_cast<map::DoorMark>(Draw(confusion_.false_mark));
  const auto& rows = class_right ? confusion_.mark_read : confusion_.mark_read_missized;
  return static_cast<map::DoorMark>(Draw(rows[static_cast<int>(index_.mark(truth))]));
}

const StreamEdge* SensedStream::At(int i) {
  while (static_cast<int>(edges_.size()) <= i && !ended_) ProcessNextTrueEdge();
  return i < static_cast<int>(edges_.size()) ? &edges_[i] : nullptr;
}

void SensedStream::ProcessNextTrueEdge() {
  const int g = next_edge_;
  if (g < 0) {
    FlushRun(false);
    ended_ = true;
    return;
  }
  const int dir = start_.dir;
  const double a = next_pos_;
  const double len = index_.metric(g);
  const double b = a + len;
  const double start_angle = dir > 0 ? index_.angle_start(g) : index_.angle_end(g);
  next_edge_ = index_.Step(g, dir);
  next_pos_ = b;

  const map::SymbolCode code = index_.code(g);
  Piece p;
  p.a = a;
  p.b = b;
  p.truth = g;
  p.start_angle = start_angle;
  if (map::IsDoorCode(code)) {
    SenseDoor(p, code, len);
    return;
  }
  const Confusion::Before before = before_;
  before_ = Confusion::Before::kUnknown;
  // A door after a short wall of a row is read by the door before that wall.
  row_door_before_ =
      code == map::kWallCode && index_.in_row(g) ? before : Confusion::Before::kUnknown;
  if (code == map::kWallCode) {
    if (leaf_to_next_in_ > 0.0) {
      // The other leaf of the door before, read as part of this wall.
      p.a -= leaf_to_next_in_;
      p.error = true;
      leaf_to_next_in_ = 0.0;
    }
    SenseWall(p, len, before);
    return;
  }
  p.kind = Piece::kOther;
  p.code = code;
  p.whole_edge = true;
  AddPiece(p);
}

void SensedStream::SenseDoor(Piece p, map::SymbolCode code, double len) {
  const int k = code - 1;
  const bool row = index_.in_row(p.truth);
  // In a row, the door before the short wall in front of this one moves the missed rate and
  // the reads share what is left (Confusion::RowMissed): the filter's BayesLocalizer::RowLinked.
  const double f = row ? confusion_.RowReadFactor(k, row_door_before_) : 1.0;
  row_door_before_ = Confusion::Before::kUnknown;
  const double u = Uniform();
  if (u < confusion_.Correct(k, row) * f) {
    p.kind = Piece::kDoor;
    p.code = code;
    p.true_width_in = len;
    p.whole_edge = true;
    p.mark = DrawMark(p.truth);
  } else if (u < (confusion_.Correct(k, row) + confusion_.Missized(k, row)) * f) {
    p.kind = Piece::kDoor;
    p.code = map::DoorCode(static_cast<map::DoorClass>(DrawClass(confusion_.missized_to[k])));
    p.true_width_in = len;
    p.error = true;
    p.mark = DrawMark(p.truth, false);
    const double deficit = len - map::DoorClassWidthIn(static_cast<map::DoorClass>(p.code - 1));
    if (LeafReads() && deficit >= kLeafDeficitIn) {
      before_ = Confusion::Before::kDoorSeen;
      SenseLeaf(p, deficit);
      return;
    }
  } else {
    p.kind = Piece::kSurface;
    p.code = map::kWallCode;
    p.error = true;
    p.missed_door = true;
  }
  before_ = p.missed_door ? Confusion::Before::kDoorMissed : Confusion::Before::kDoorSeen;
  AddPiece(p);
}

bool SensedStream::LeafReads() const {
  return confusion_.leaf_split + confusion_.leaf_before + confusion_.leaf_after > 0.0;
}

void SensedStream::SenseLeaf(Piece p, double deficit) {
  const int k = index_.code(p.truth) - 1;
  p.true_width_in -= deficit;
  const double u = Uniform();
  const Confusion& cf = confusion_;
  if (u < cf.leaf_split) {
    // The other leaf as a second door, after a sliver of wall (the meeting stiles) or not.
    Piece first = p;
    first.b = p.a + p.true_width_in;
    AddPiece(first);
    Piece other = p;
    other.start_angle = 180.0;
    other.code = map::DoorCode(static_cast<map::DoorClass>(DrawClass(cf.missized_to[k])));
    other.true_width_in = map::DoorClassWidthIn(static_cast<map::DoorClass>(other.code - 1));
    other.mark = DrawMark(p.truth, false);
    other.a = first.b;
    if (Uniform() < cf.leaf_sliver) {
      Piece sliver = p;
      sliver.kind = Piece::kSurface;
      sliver.code = map::kWallCode;
      sliver.start_angle = 180.0;
      sliver.a = first.b;
      sliver.b = first.b + Uniform() * deficit;
      other.a = sliver.b;
      AddPiece(sliver);
    }
    AddPiece(other);
    return;
  }
  if (u < cf.leaf_split + cf.leaf_before) {
    // The wall just before took the first leaf: only a whole wall read as itself, the map
    // edge before the door, as the Bayes filter weighs it (the H phase).
    if (run_active_ && run_.kind == Piece::kSurface && run_pieces_ == 1 && !run_error_ &&
        !run_lower_bound_ && first_emitted_ && run_.truth == index_.Step(p.truth, -start_.dir) &&
        Coplanar(p.start_angle)) {
      run_.b += deficit;
      run_error_ = true;
      p.a += deficit;
    }
  } else if (u < cf.leaf_split + cf.leaf_before + cf.leaf_after) {
    // The wall just after takes the other leaf, where it is a wall on the same plane.
    const int w = index_.Step(p.truth, start_.dir);
    const double a_out = w < 0 ? 0.0 : start_.dir > 0 ? index_.angle_start(w) : index_.angle_end(w);
    if (w >= 0 && index_.code(w) == map::kWallCode && Coplanar(a_out)) {
      p.b -= deficit;
      leaf_to_next_in_ = deficit;
    }
  }
  AddPiece(p);
}

void SensedStream::SenseWall(Piece p, double len, Confusion::Before before) {
  const bool row = index_.in_row(p.truth);
  double false_door = confusion_.FalseDoorIn(len, row, before);
  for (int held = 0; false_door > 0.0 && Uniform() < false_door;) {
    const int c = DrawClass(confusion_.false_class);
    const double w = map::DoorClassWidthIn(static_cast<map::DoorClass>(c));
    const double at = Uniform() * std::max(0.0, len - w);
    // A wall narrower than the ribbon cannot hold a false door of that class.
    if (len <= w) break;
    // The ribbon splits the wall: W1, a false door, W2 (§6.4.2 false positive); with the
    // per-inch model W2 may hold another, as the Bayes filter allows (a row's wall not).
    p = SplitByFalseDoor(p, c, w, at);
    len = p.b - p.a;
    if (row || !confusion_.AnotherFalseDoor(++held)) break;
    false_door = confusion_.FalseDoorIn(len, false);
  }
  if (!p.error) {
    p.kind = Piece::kSurface;
    p.code = map::kWallCode;
    p.whole_edge = true;
  }
  AddPiece(p);
}

SensedStream::Piece SensedStream::SplitByFalseDoor(const Piece& p, int false_class, double width_in,
                                                   double at_in) {
  const double a = p.a;
  Piece w1 = p;
  w1.kind = Piece::kSurface;
  w1.b = a + at_in;
  w1.error = true;
  Piece door = p;
  door.kind = Piece::kDoor;
  door.code = map::DoorCode(static_cast<map::DoorClass>(false_class));
  door.a = a + at_in;
  door.b = a + at_in + width_in;
  door.true_width_in = width_in;
  door.error = true;
  door.mark = DrawMark(-1);
  door.start_angle = 180.0;
  Piece w2 = p;
  w2.kind = Piece::kSurface;
  w2.a = door.b;
  w2.error = true;
  w2.whole_edge = false;
  w2.start_angle = 180.0;
  AddPiece(w1);
  AddPiece(door);
  return w2;
}

void SensedStream::AddPiece(const Piece& piece) {
  if (piece.b <= 0.0) return;  // behind the start point: never seen
  Piece p = piece;
  bool clipped = false;
  if (p.a < 0.0 && p.kind != Piece::kDoor) {
    p.a = 0.0;  // seen from the start point on
    clipped = true;
  }
  if (p.kind == Piece::kSurface && run_active_ && run_.kind == Piece::kSurface &&
      (run_last_missed_ || p.missed_door) && Coplanar(p.start_angle)) {
    // The jamb of a missed door on a flat wall is not a sensed boundary.
    run_.b = p.b;
    run_.truth = p.truth;
    ++run_pieces_;
    run_error_ = true;
    run_whole_ = false;
    run_last_missed_ = p.missed_door;
    run_missed_ += p.missed_door;
    return;
  }
  FlushRun(p.kind == Piece::kDoor);
  if (p.kind == Piece::kDoor) {
    EmitDoor(p);
    return;
  }
  run_active_ = true;
  run_ = p;
  run_pieces_ = 1;
  run_error_ = p.error;
  run_whole_ = p.whole_edge;
  run_lower_bound_ = clipped;
  run_last_missed_ = p.missed_door;
  run_missed_ = p.missed_door;
  if (p.kind == Piece::kOther) FlushRun(false);  // other edge types never merge
}

void SensedStream::FlushRun(bool door_follows) {
  if (!run_active_) return;
  run_active_ = false;
  StreamEdge e;
  const double true_len = run_.b - run_.a;
  e.sensed.code = run_.code;
  e.sensed.metric_in = MeasureLength(true_len, run_lower_bound_ ? 1 : 2);
  if (run_missed_ > 0 &&
      (confusion_.missed_wall_bias_in != 0.0 || confusion_.missed_wall_var_in2 > 0.0)) {
    // ErrorModel::wall_over_missed_door: longer and looser per missed door it runs over.
    double extra = run_missed_ * confusion_.missed_wall_bias_in;
    if (confusion_.missed_wall_var_in2 > 0.0) {
      extra += std::sqrt(run_missed_ * confusion_.missed_wall_var_in2) * Gauss();
    }
    e.sensed.metric_in = std::max(std::min(true_len, 0.5), e.sensed.metric_in + extra);
  }
  e.sensed.metric_is_lower_bound = run_lower_bound_;
  e.sensed.angle_deg = first_emitted_ ? run_.start_angle : std::numeric_limits<double>::quiet_NaN();
  e.truth = run_.truth;
  e.end_in = run_.b;
  bool faithful = !run_error_ && run_pieces_ == 1 && run_whole_;
  if (faithful) {
    const double m = index_.metric(run_.truth);
    const double allow = std::max(tolerance_.metric_abs_in, tolerance_.metric_rel * m) + 1e-9;
    faithful = run_lower_bound_ ? m >= e.sensed.metric_in - allow
                                : std::abs(m - e.sensed.metric_in) <= allow;
  }
  e.faithful = faithful;
  e.with_next = door_follows;
  first_emitted_ = true;
  edges_.push_back(e);
}

void SensedStream::EmitDoor(const Piece& p) {
  StreamEdge e;
  e.sensed.code = p.code;
  e.sensed.mark = p.mark;
  e.sensed.metric_in = MeasureWidth(p.true_width_in, static_cast<map::DoorClass>(p.code - 1));
  e.sensed.angle_deg = first_emitted_ ? p.start_angle : std::numeric_limits<double>::quiet_NaN();
  e.truth = p.truth;
  e.end_in = p.b;
  e.faithful = !p.error;
  first_emitted_ = true;
  edges_.push_back(e);
}

double SensedStream::MeasureLength(double true_len, int jambs) {
  double m = true_len * (1.0 + scale_error_);
  if (noise_.wheel_walk_sigma_in_per_sqrt_in > 0) {
    m += noise_.wheel_walk_sigma_in_per_sqrt_in * std::sqrt(std::max(0.0, true_len)) * Gauss();
  }
  if (noise_.jamb_sigma_in > 0) {
    for (int j = 0; j < jambs; ++j) m += noise_.jamb_sigma_in * Gauss();
  }
  // A measured length is positive: two jambs cannot be seen in the wrong order.
  return std::max(m, std::min(true_len, 0.5));
}

double SensedStream::MeasureWidth(double true_width, map::DoorClass sensed_class) {
  const ClassRegion r = noise_.class_region_in[static_cast<int>(sensed_class)];
  const double lo = r.lo_in, hi = r.hi_in - 1e-6;
  const double sigma = noise_.width_sigma_rel * true_width;
  if (sigma <= 0.0) return std::clamp(true_width, lo, hi);
  // The classifier put this width in `sensed_class`: a normal error about the true width,
  // conditioned on landing in that class's region.
  for (int i = 0; i < 16; ++i) {
    const double x = true_width + sigma * Gauss();
    if (x >= lo && x <= hi) return x;
  }
  // Far in the tail: the truncated normal is close to an exponential beyond the boundary.
  const double u = 1.0 - Uniform();
  if (true_width < lo) return std::min(hi, lo - sigma * sigma / (lo - true_width) * std::log(u));
  if (true_width > hi) return std::max(lo, hi + sigma * sigma / (true_width - hi) * std::log(u));
  return true_width;
}

}  // namespace stickrep::recovery
