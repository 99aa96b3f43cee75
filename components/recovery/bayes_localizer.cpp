#include "recovery/bayes_localizer.h"

#include <algorithm>
#include <cmath>

namespace stickrep::recovery {

namespace {

constexpr double kSqrt2Pi = 2.5066282746310002;
// Lengths are densities per inch; an unexplained metric edge is spread over about this
// many inches so that the outlier competes with them on the same footing.
constexpr double kOutlierSpanIn = 120.0;
// Belief below this (of a normalised total of 1) is dropped: it can only come back through
// a chain of unexplained edges, each of which costs `outlier`.
constexpr double kPruneBelow = 1e-15;

bool Coplanar(double angle_deg) { return std::abs(angle_deg - 180.0) < 1.0; }

double ClassWidth(map::SymbolCode code) {
  return map::DoorClassWidthIn(static_cast<map::DoorClass>(code - 1));
}

}  // namespace

BayesLocalizer::BayesLocalizer(const map::MatchIndex& index, BayesModel model)
    : index_(index), model_(std::move(model)) {
  states_ = 2 * index.EdgeCount();
  for (int g = 0; g < index.EdgeCount(); ++g) total_length_in_ += index.metric(g);
  for (auto* v : {&n_,   &i1_,  &i2_,        &c1_,          &c2_,    &nn_,     &ni1_, &ni2_,
                  &nc1_, &nc2_, &s1_,        &s2_,          &t_,     &h_,      &ns1_, &ns2_,
                  &nt_,  &nh_,  &prev_seen_, &prev_missed_, &nseen_, &nmissed_}) {
    v->assign(states_, 0.0);
  }
  for (auto* v : {&lb1_, &lb2_, &nlb1_, &nlb2_, &fd1_, &fd2_, &nfd1_, &nfd2_}) {
    v->assign(states_, 0);
  }
}

void BayesLocalizer::Reset() {
  std::fill(n_.begin(), n_.end(), 0.0);
  ClearPrev();
  std::fill(i1_.begin(), i1_.end(), 0.0);
  std::fill(i2_.begin(), i2_.end(), 0.0);
  ClearLeafPhases();
  outside_ = 0.0;
  status_ = RecoveryStatus::kEmpty;
  best_ = PoseBelief{};
  edges_ = 0;
  above_ = 0;
  skip_partial_ = false;
  edge_best_ = PoseBelief{};
  silent_in_ = 0.0;
  silence_.clear();
  silence_norm_ = 1.0;
}

void BayesLocalizer::Reverse(double travelled_in) {
  if (states_ == 0 || edges_ == 0) return;
  std::fill(nn_.begin(), nn_.end(), 0.0);
  const bool measured = std::isfinite(travelled_in) && travelled_in > 0.0;
  // S1(d), S2(d), T(d): a leaf of door d was sensed as a door, so going back the robot
  // meets that leaf again, as it meets door d from N(d).
  for (int s = 0; s < states_; ++s) n_[s] += s1_[s] + s2_[s] + t_[s];
  for (int g = 0; g < index_.EdgeCount(); ++g) {
    for (const int dir : {+1, -1}) {
      const int s = State(g, dir);
      // At the far end of g: the robot is inside the next edge and will leave it at its
      // far end going back. (At the end of an open ring there is no next edge: dropped.)
      const int next = index_.Step(g, dir);
      if (next >= 0 && n_[s] > 0.0) {
        if (measured) {
          ReverseAfter(next, dir, n_[s], travelled_in);
        } else {
          nn_[State(next, -dir)] += n_[s];
        }
      }
      // Inside wall g around a false door: going back it leaves g at g's start.
      nn_[State(g, -dir)] += i1_[s] + i2_[s];
      // H(g): the wall before door g held g's first leaf, read as wall; going back the robot
      // sees that wall again (leaf and all) and leaves it at its start.
      const int before = index_.Step(g, -dir);
      if (before >= 0 && h_[s] > 0.0) nn_[State(before, -dir)] += h_[s];
    }
  }
  n_.swap(nn_);
  std::fill(i1_.begin(), i1_.end(), 0.0);
  std::fill(i2_.begin(), i2_.end(), 0.0);
  ClearLeafPhases();
  ClearPrev();  // going back, the door before each edge is the one on its other side
  skip_partial_ = true;
  // Moving the belief is no new evidence: the confirmation count stays as it was.
  const int above = above_;
  const RecoveryStatus status = status_;
  Normalise();
  above_ = above;
  status_ = status;
}

void BayesLocalizer::ReverseAfter(int first, int dir, double mass, double travelled_in) {
  // The robot went travelled_in past the last sensed edge into `first` and on, seeing no
  // door, then turned back. It is in the edge of the stretch ahead that holds that
  // distance: every door before it was missed. The stretch ends where the follower would
  // have turned (a corner) or at the end of an open ring; a reversal there (a hallway end)
  // absorbs whatever odometry overshoots.
  const auto below = [](double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); };
  // An outlier's share stays where the reversal without the distance would put it: a
  // stretch the map does not explain (a door the map lacks, a wrong odometer) must not
  // empty the belief.
  nn_[State(first, -dir)] += mass * model_.settings.outlier;
  double start = 0.0, weight = 1.0;
  int cur = first;
  int missed = 0;
  for (int m = 0; m < index_.EdgeCount() && cur >= 0; ++m) {
    // A step's side runs across the hallway between corners of opposite sense: the base
    // passes it without travelling along it.
    const double a_in = index_.angle_start(cur), a_end = index_.angle_end(cur);
    const double step_in = model_.settings.max_step_in;
    const bool side = index_.metric(cur) <= step_in && std::abs(a_in - 180.0) >= 45.0 &&
                      std::abs(a_end - 180.0) >= 45.0 && (a_in - 180.0) * (a_end - 180.0) < 0.0;
    const double len = side ? 0.0 : index_.metric(cur);
    const double sigma = std::max(1.0, model_.noise.WallSigmaIn(start + len));
    const int after = index_.Step(cur, dir);
    const double a_out = dir > 0 ? index_.angle_end(cur) : index_.angle_start(cur);
    // The follower turns at a corner, not at a step's corners (a pilaster's sides).
    const bool last = after < 0 || (std::abs(a_out - 180.0) >= 45.0 &&
                                    index_.metric(cur) > step_in &&
                                    index_.metric(after) > step_in);
    const double reach = below((travelled_in - start) / sigma);
    const double beyond = last ? 0.0 : below((travelled_in - start - len) / sigma);
    nn_[State(cur, -dir)] += mass * weight * std::max(0.0, reach - beyond);
    if (last || start > travelled_in + 4.0 * sigma) break;
    if (map::IsDoorCode(index_.code(cur))) {
      if (++missed > model_.settings.max_missed_doors) break;
      weight *= Missed(cur);
    }
    start += len;
    cur = after;
  }
}

double BayesLocalizer::Missed(int door) const {
  return model_.confusion.Missed(index_.code(door) - 1, index_.in_row(door));
}

bool BayesLocalizer::RowLinked(int wall, int door) const {
  return model_.confusion.row_missed_by_before && index_.code(wall) == map::kWallCode &&
         index_.in_row(wall) && index_.in_row(door);
}

double BayesLocalizer::MissedAfter(int wall, int door, Confusion::Before before) const {
  if (!RowLinked(wall, door)) return Missed(door);
  return model_.confusion.RowMissed(index_.code(door) - 1, before);
}

double BayesLocalizer::ReadFactorAfter(int wall, int door, Confusion::Before before) const {
  if (!RowLinked(wall, door)) return 1.0;
  return model_.confusion.RowReadFactor(index_.code(door) - 1, before);
}

double BayesLocalizer::MixedFrom(int from, int door, RowRate rate) const {
  const double seen = prev_seen_[from], missed = prev_missed_[from];
  using B = Confusion::Before;
  return seen * (this->*rate)(from / 2, door, B::kDoorSeen) +
         missed * (this->*rate)(from / 2, door, B::kDoorMissed) +
         (1.0 - seen - missed) * (this->*rate)(from / 2, door, B::kUnknown);
}

void BayesLocalizer::AddEnd(int s, double mass, Confusion::Before before) {
  nn_[s] += mass;
  if (before == Confusion::Before::kDoorSeen) nseen_[s] += mass;
  if (before == Confusion::Before::kDoorMissed) nmissed_[s] += mass;
}

void BayesLocalizer::ClearPrev() {
  std::fill(prev_seen_.begin(), prev_seen_.end(), 0.0);
  std::fill(prev_missed_.begin(), prev_missed_.end(), 0.0);
}

double BayesLocalizer::FalseDoorAt(int wall, Confusion::Before before) const {
  return model_.confusion.FalseDoorIn(index_.metric(wall), index_.in_row(wall), before);
}

double BayesLocalizer::WallDensity(double measured, double true_len) const {
  const double sigma = std::max(1.0, model_.noise.WallSigmaIn(std::max(true_len, 0.0)));
  const double z = (measured - true_len) / sigma;
  return std::exp(-0.5 * z * z) / (kSqrt2Pi * sigma);
}

double BayesLocalizer::WallDensityOverMissed(double measured, double true_len, int missed,
                                             double extra_var) const {
  const Confusion& c = model_.confusion;
  const double mean = true_len + missed * c.missed_wall_bias_in;
  const double var = extra_var + missed * c.missed_wall_var_in2;
  if (var <= 0.0 && mean == true_len) return WallDensity(measured, true_len);
  return WidenedWallDensity(measured, mean, true_len, var);
}

double BayesLocalizer::WidenedWallDensity(double measured, double mean, double len_in,
                                          double extra_var) const {
  const double base = model_.noise.WallSigmaIn(std::max(len_in, 0.0));
  const double sigma = std::max(1.0, std::sqrt(base * base + extra_var));
  const double z = (measured - mean) / sigma;
  return std::exp(-0.5 * z * z) / (kSqrt2Pi * sigma);
}

double BayesLocalizer::FalseDoorVar(int s) const {
  // The false door's two jambs and its measured width.
  const SensingNoise& nz = model_.noise;
  const double wsig = nz.width_sigma_rel * (c2_[s] - c1_[s]);
  return 2.0 * nz.jamb_sigma_in * nz.jamb_sigma_in + wsig * wsig;
}

double BayesLocalizer::AngleFactor(int g, int dir, const map::SensedEdge& e) const {
  if (std::isnan(e.angle_deg)) return 1.0;
  const double a = dir > 0 ? index_.angle_start(g) : index_.angle_end(g);
  return std::abs(a - e.angle_deg) <= model_.settings.angle_tolerance_deg ? 1.0
                                                                          : model_.settings.outlier;
}

RecoveryStatus BayesLocalizer::Add(const map::SensedEdge& edge) {
  if (CheckSensedEdge(edge)) {
    ++rejected_;
    return status_;
  }
  if (states_ == 0) return status_;
  if (skip_partial_) {
    skip_partial_ = false;
    if (edge.metric_is_lower_bound) return status_;
  }
  if (edges_ == 0) {
    First(edge);
  } else {
    Next(edge);
  }
  WeighMark(edge);
  last_ = edge;
  ++edges_;
  Normalise();
  return status_;
}

void BayesLocalizer::WeighMark(const map::SensedEdge& e) {
  const Confusion& cf = model_.confusion;
  if (!cf.marks || !map::IsDoorCode(e.code)) return;
  // Every phase of state s holds the sensed door at map edge s / 2: that door's leaf, or a
  // false door where the map has no door. The N phase of a door of the sensed class holds
  // it read right; the leaf phases, a leaf of a double door.
  for (int s = 0; s < states_; ++s) {
    const int g = s / 2;
    if (!map::IsDoorCode(index_.code(g))) {
      const double f = cf.FalseDoorMarkLikelihood(e.mark);
      for (auto* v : {&n_, &i1_, &i2_, &s1_, &s2_, &t_, &h_}) (*v)[s] *= f;
      continue;
    }
    const map::DoorMark truth = index_.mark(g);
    const double right = cf.MarkLikelihood(e.mark, truth, index_.code(g) == e.code);
    const double leaf = cf.MarkLikelihood(e.mark, truth, false);
    for (auto* v : {&n_, &i1_, &i2_}) (*v)[s] *= right;
    for (auto* v : {&s1_, &s2_, &t_, &h_}) (*v)[s] *= leaf;
  }
}

void BayesLocalizer::First(const map::SensedEdge& e) {
  outside_ = 0.0;
  std::fill(n_.begin(), n_.end(), 0.0);
  ClearPrev();
  std::fill(i1_.begin(), i1_.end(), 0.0);
  std::fill(i2_.begin(), i2_.end(), 0.0);
  ClearLeafPhases();
  AddPrior(e, 1.0);
}

void BayesLocalizer::AddPrior(const map::SensedEdge& e, double weight) {
  const Confusion& cf = model_.confusion;
  const double eps = model_.settings.outlier;
  const bool door = map::IsDoorCode(e.code);
  const double unit = door ? 1.0 : 1.0 / kOutlierSpanIn;
  for (int g = 0; g < index_.EdgeCount(); ++g) {
    const double len = index_.metric(g);
    const map::SymbolCode code = index_.code(g);
    // Prior: the start is uniform along the walls, so edge g holds it with len / total.
    const double prior = len / total_length_in_;
    double pn = 0.0, pi1 = 0.0, pi2 = 0.0;
    ChainedPrior chained[2];  // per direction, see below
    if (door) {
      if (map::IsDoorCode(code)) {
        const int k = code - 1, c = e.code - 1;
        const bool row = index_.in_row(g);
        pn = prior * (k == c ? cf.Correct(k, row) : cf.Missized(k, row) * cf.missized_to[k][c]);
      } else if (code == map::kWallCode && len > ClassWidth(e.code)) {
        // The robot starts beside a false door in a wall.
        pi2 = FalseDoorAt(g) * cf.false_class[e.code - 1] * ClassWidth(e.code) / total_length_in_;
      }
    } else if (code == e.code) {
      const bool wall = code == map::kWallCode;
      const double clean = wall ? 1.0 - FalseDoorAt(g) : 1.0;
      if (e.metric_is_lower_bound) {
        // The part seen from a uniform start point: density 1/len for any length up to len.
        const double sigma = std::max(1.0, model_.noise.WallSigmaIn(len));
        const double over = std::max(0.0, e.metric_in - len) / sigma;
        const double fit = std::exp(-0.5 * over * over);
        pn = clean * fit / total_length_in_;
        // ... or the part up to a false door ahead in the same wall.
        if (wall) {
          pi1 = FalseDoorAt(g) * 0.5 * fit * RoomForFalseDoor(len, e.metric_in) / total_length_in_;
        }
        if (wall) {
          // ... or it began in an earlier wall or door and ran over missed doors into this
          // wall (one sensed wall over a flat stretch). Direction-dependent.
          for (const int dir : {+1, -1}) {
            chained[dir > 0 ? 0 : 1] = PriorOverMissedDoors(g, dir, sigma, e);
          }
        }
      } else {
        pn = clean * WallDensity(e.metric_in, len) / index_.EdgeCount();
      }
    }
    for (const int dir : {+1, -1}) {
      if (prior_dir_ != 0 && dir != prior_dir_) continue;
      const int s = State(g, dir);
      const ChainedPrior& ch = chained[dir > 0 ? 0 : 1];
      n_[s] += weight * (ch.end + pn + eps * unit * prior);
      // W1 is known only from below: the seen part of the wall for a start in it, less for
      // a run into it that began behind. One W1 is kept per state, the larger share's.
      const double add1 = weight * (pi1 + ch.first_part);
      if (add1 > 0.0 && add1 >= i1_[s]) {
        c1_[s] = ch.first_part > pi1 ? ch.w1_min_in : e.metric_in;
        lb1_[s] = 1;
        fd1_[s] = 0;
      }
      i1_[s] += add1;
      if (pi2 > 0.0 && weight * pi2 >= i2_[s]) {
        c2_[s] = door ? e.metric_in : 0.0;
        lb2_[s] = 1;
        fd2_[s] = 1;
      }
      i2_[s] += weight * pi2;
    }
  }
}

BayesLocalizer::ChainedPrior BayesLocalizer::PriorOverMissedDoors(int g, int dir, double sigma,
                                                                  const map::SensedEdge& e) const {
  ChainedPrior out;
  const double len = index_.metric(g);
  const double x = e.metric_in;
  // Wall g is entered past a missed door: it holds a false door at the rate after one.
  const double pf_g = FalseDoorAt(g, Confusion::Before::kDoorMissed);
  double near = 0.0;  // how far behind g's start the element considered ends
  double p = 1.0;     // the doors between missed, the walls between without a false door
  // The start was inside the element `length` long that ends `near` behind g's start.
  const auto start_in = [&](double length) {
    const double far = near + length;
    // The sensed wall ended at g's far end: x = t + len for a start t behind g's start.
    if (x >= near + len - sigma && x <= far + len + sigma) {
      out.end += p * (1.0 - pf_g) / total_length_in_;
    }
    // ... or in g's first part W1 = x - t, before a false door (uniform over the wall).
    const double lo = std::max(near, x - len), hi = std::min(far, x);
    if (pf_g > 0.0 && hi > lo) {
      const double w1_min = std::max(0.0, x - far);
      const double mass =
          p * pf_g * (hi - lo) / (len * total_length_in_) * RoomForFalseDoor(len, w1_min);
      // W1 is known only from below, over every element the start may lie in.
      out.w1_min_in = out.first_part > 0.0 ? std::min(out.w1_min_in, w1_min) : w1_min;
      out.first_part += mass;
    }
    near = far;
  };
  int cur = g;
  for (int m = 0; m < model_.settings.max_missed_doors; ++m) {
    const int d = index_.Step(cur, -dir);
    if (d < 0 || !map::IsDoorCode(index_.code(d))) break;
    const double a_d = dir > 0 ? index_.angle_end(d) : index_.angle_start(d);
    if (!Coplanar(a_d)) break;
    p *= Missed(d);
    start_in(index_.metric(d));  // inside the missed door itself
    const int w = index_.Step(d, -dir);
    if (w < 0 || index_.code(w) != map::kWallCode) break;
    const double a_w = dir > 0 ? index_.angle_end(w) : index_.angle_start(w);
    if (!Coplanar(a_w)) break;
    // The wall before the missed door holds no false door in the part seen.
    p *= 1.0 - FalseDoorAt(w);
    start_in(index_.metric(w));
    cur = w;
  }
  return out;
}

void BayesLocalizer::Next(const map::SensedEdge& e) {
  const bool door = map::IsDoorCode(e.code);
  std::fill(nn_.begin(), nn_.end(), 0.0);
  std::fill(ni1_.begin(), ni1_.end(), 0.0);
  std::fill(ni2_.begin(), ni2_.end(), 0.0);
  for (auto* v : {&ns1_, &ns2_, &nt_, &nh_, &nseen_, &nmissed_})
    std::fill(v->begin(), v->end(), 0.0);
  // Belief that passes out through a corridor's open end: the ring says nothing of where
  // the robot goes from there (across the corridor beyond, into a hall), so that belief
  // starts again from the prior, with what was sensed after it as a first edge. Belief that
  // left with the wall sensed last time (outside_) starts again here too.
  double leaving = outside_;
  outside_ = 0.0;
  // A kidnap before this edge: that share of every state starts again from the prior too.
  const double kidnap = model_.settings.kidnap_per_edge;
  if (kidnap > 0.0) {
    for (auto* v : {&n_, &i1_, &i2_, &s1_, &s2_, &t_, &h_}) {
      for (double& p : *v) p *= 1.0 - kidnap;
    }
    leaving = leaving * (1.0 - kidnap) + kidnap;
  }

  for (int s = 0; s < states_; ++s) {
    const int g = s / 2;
    const int dir = (s & 1) ? -1 : +1;
    const double pn = n_[s];
    if (pn > 0.0) NextFromEnd(g, dir, pn, e, &leaving);
    const double p1 = i1_[s];
    if (p1 > 0.0) NextFromFirstPart(s, p1, e);
    const double p2 = i2_[s];
    if (p2 > 0.0) NextFromSecondPart(s, p2, e);
    if (s1_[s] > 0.0 || s2_[s] > 0.0 || t_[s] > 0.0 || h_[s] > 0.0) NextFromLeafPhases(s, e);
  }
  n_.swap(nn_);
  i1_.swap(ni1_);
  i2_.swap(ni2_);
  c1_.swap(nc1_);
  c2_.swap(nc2_);
  lb1_.swap(nlb1_);
  lb2_.swap(nlb2_);
  fd1_.swap(nfd1_);
  fd2_.swap(nfd2_);
  s1_.swap(ns1_);
  s2_.swap(ns2_);
  t_.swap(nt_);
  h_.swap(nh_);
  if (leaving > 0.0) {
    // Outside the ring the robot met the next wall somewhere along it: a partial wall.
    map::SensedEdge after = e;
    if (!door) after.metric_is_lower_bound = true;
    AddPrior(after, leaving);
  }
  for (int s = 0; s < states_; ++s) {
    prev_seen_[s] = n_[s] > 0.0 ? nseen_[s] / n_[s] : 0.0;
    prev_missed_[s] = n_[s] > 0.0 ? nmissed_[s] / n_[s] : 0.0;
  }
}

void BayesLocalizer::NextFromEnd(int g, int dir, double pn, const map::SensedEdge& e,
                                 double* leaving) {
  const double eps = model_.settings.outlier;
  const bool door = map::IsDoorCode(e.code);
  const bool wall = e.code == map::kWallCode;
  const double unit = door ? 1.0 : 1.0 / kOutlierSpanIn;
  const int n1 = index_.Step(g, dir);
  if (n1 < 0) return;
  if (index_.open_end(n1)) {
    *leaving += pn;
    return;
  }
  const int s1 = State(n1, dir);
  const map::SymbolCode code1 = index_.code(n1);
  const double angle = AngleFactor(n1, dir, e);
  nn_[s1] += pn * eps * unit;  // an edge the model does not explain
  // A door state at its far end was (almost always) reached by sensing the door.
  const Confusion::Before before =
      map::IsDoorCode(index_.code(g)) ? Confusion::Before::kDoorSeen : Confusion::Before::kUnknown;
  if (wall && code1 == map::kWallCode) {
    NextWallFromEnd(n1, dir, pn, angle, e, before);
  } else if (wall && map::IsDoorCode(code1)) {
    // A missed door seen as wall surface (at a corner), maybe with the wall after it.
    const double d = index_.metric(n1);
    const double missed = MixedFrom(State(g, dir), n1, &BayesLocalizer::MissedAfter);
    nn_[s1] += pn * angle * missed * WallDensity(e.metric_in, d);
    const int w = index_.Step(n1, dir);
    if (w >= 0 && index_.code(w) == map::kWallCode) {
      const double a_out = dir > 0 ? index_.angle_start(w) : index_.angle_end(w);
      if (Coplanar(a_out)) {
        AddEnd(State(w, dir),
               pn * angle * missed * (1.0 - FalseDoorAt(w, Confusion::Before::kDoorMissed)) *
                   WallDensity(e.metric_in, d + index_.metric(w)),
               Confusion::Before::kDoorMissed);
      }
    }
  } else if (door && map::IsDoorCode(code1)) {
    // Read: its rates by the door before the wall the state ended in (a row's doors).
    NextLeafFromEnd(n1, dir, pn * MixedFrom(State(g, dir), n1, &BayesLocalizer::ReadFactorAfter),
                    angle, e);
  } else if (!door && !wall && code1 == e.code) {
    nn_[s1] += pn * angle * WallDensity(e.metric_in, index_.metric(n1));
  }
}

void BayesLocalizer::NextWallFromEnd(int n1, int dir, double pn, double angle,
                                     const map::SensedEdge& e, Confusion::Before before) {
  const double pf = FalseDoorAt(n1, before);
  const int s1 = State(n1, dir);
  const double len1 = index_.metric(n1);
  AddEnd(s1, pn * angle * (1.0 - pf) * WallDensity(e.metric_in, len1), before);
  const int n2 = index_.Step(n1, dir);
  if (n2 >= 0 && index_.open_end(n2)) {
    // The wall before an open end, run on out through it to wherever the next edge
    // was seen: the robot is outside from the next edge on.
    const double reach = model_.settings.open_end_reach_in;
    const double sigma = std::max(1.0, model_.noise.WallSigmaIn(len1));
    if (e.metric_in >= len1 - 2.0 * sigma && e.metric_in <= len1 + reach) {
      outside_ += pn * angle * (1.0 - pf) / (reach + 2.0 * sigma);
    }
  }
  if (e.metric_in <= len1) {
    // W1 of a wall holding a false door: the ribbon is anywhere in the wall.
    AddFirstPart(s1, pn * angle * pf, e.metric_in);
  }
  NextWallOverMissedDoors(n1, dir, pn, angle, e, before);
  NextWallBeforeLeaf(n1, dir, pn, angle, e, before);
}

double BayesLocalizer::LeafDeficit(int k, int c) {
  return map::DoorClassWidthIn(static_cast<map::DoorClass>(k)) -
         map::DoorClassWidthIn(static_cast<map::DoorClass>(c));
}

double BayesLocalizer::LeafRead(int door, int c) const {
  const int k = index_.code(door) - 1;
  if (LeafDeficit(k, c) < kLeafDeficitIn) return 0.0;
  const Confusion& cf = model_.confusion;
  return cf.Missized(k, index_.in_row(door)) * cf.missized_to[k][c];
}

double BayesLocalizer::LeafWallWeight(int door, int c, double wall_in, double len) const {
  const int k = index_.code(door) - 1;
  double sum = 0.0;
  for (int leaf = 0; leaf < kDoorClasses; ++leaf) {
    if (c >= 0 && leaf != c) continue;
    const double p = LeafRead(door, leaf);
    if (p > 0.0) sum += p * WallDensity(wall_in, len + LeafDeficit(k, leaf));
  }
  return sum;
}

void BayesLocalizer::NextLeafFromEnd(int n1, int dir, double pn, double angle,
                                     const map::SensedEdge& e) {
  const Confusion& cf = model_.confusion;
  const int s1 = State(n1, dir);
  const int k = index_.code(n1) - 1, c = e.code - 1;
  const bool row = index_.in_row(n1);
  const double pc = k == c ? cf.Correct(k, row) : cf.Missized(k, row) * cf.missized_to[k][c];
  // A read as one leaf: the rest of the door as a second door next (S1), in the wall after
  // (T), or nowhere; the share of it that was in the wall before came through H instead.
  const double leaf = LeafRead(n1, c);
  const double rest = 1.0 - cf.leaf_split - cf.leaf_before - cf.leaf_after;
  nn_[s1] += pn * angle * (pc - leaf + leaf * rest);
  if (leaf > 0.0) {
    ns1_[s1] += pn * angle * leaf * cf.leaf_split;
    nt_[s1] += pn * angle * leaf * cf.leaf_after;
  }
}

void BayesLocalizer::NextWallBeforeLeaf(int n1, int dir, double pn, double angle,
                                        const map::SensedEdge& e, Confusion::Before before) {
  const Confusion& cf = model_.confusion;
  if (cf.leaf_before <= 0.0) return;
  const int n2 = index_.Step(n1, dir);
  if (n2 < 0 || !map::IsDoorCode(index_.code(n2))) return;
  const double a_in = dir > 0 ? index_.angle_start(n2) : index_.angle_end(n2);
  if (!Coplanar(a_in)) return;
  const double w =
      LeafWallWeight(n2, -1, e.metric_in, index_.metric(n1)) * ReadFactorAfter(n1, n2, before);
  nh_[State(n2, dir)] += pn * angle * (1.0 - FalseDoorAt(n1, before)) * cf.leaf_before * w;
}

void BayesLocalizer::NextFromLeafPhases(int s, const map::SensedEdge& e) {
  const Confusion& cf = model_.confusion;
  const double eps = model_.settings.outlier;
  const bool door = map::IsDoorCode(e.code);
  const int d = s / 2;
  const int dir = (s & 1) ? -1 : +1;
  const int k = index_.code(d) - 1;
  nn_[s] += (s1_[s] + s2_[s] + t_[s] + h_[s]) * eps * (door ? 1.0 : 1.0 / kOutlierSpanIn);
  const double flat = std::isnan(e.angle_deg) || Coplanar(e.angle_deg) ? 1.0 : eps;
  if (door) {
    // The other leaf, its class as the door's leaf reads go.
    const double other = cf.missized_to[k][e.code - 1];
    nn_[s] += flat * other * (s1_[s] * (1.0 - cf.leaf_sliver) + s2_[s]);
    if (h_[s] > 0.0 && last_.code == map::kWallCode) {
      // The leaf after the wall that held the first one: its class given that wall.
      const int before = index_.Step(d, -dir);
      const double len = before >= 0 ? index_.metric(before) : 0.0;
      const double all = LeafWallWeight(d, -1, last_.metric_in, len);
      if (all > 0.0) {
        nn_[s] += h_[s] * flat * LeafWallWeight(d, e.code - 1, last_.metric_in, len) / all;
      }
    }
    return;
  }
  if (e.code != map::kWallCode || !map::IsDoorCode(last_.code)) return;
  const double deficit = LeafDeficit(k, last_.code - 1);
  if (s1_[s] > 0.0 && deficit > 0.0 && e.metric_in <= deficit) {
    ns2_[s] += s1_[s] * flat * cf.leaf_sliver / deficit;  // the sliver, anywhere up to it
  }
  const int w = index_.Step(d, dir);
  if (t_[s] > 0.0 && w >= 0 && index_.code(w) == map::kWallCode) {
    const double a_out = dir > 0 ? index_.angle_start(w) : index_.angle_end(w);
    if (Coplanar(a_out)) {
      AddEnd(State(w, dir),
             t_[s] * flat * (1.0 - FalseDoorAt(w, Confusion::Before::kDoorSeen)) *
                 WallDensity(e.metric_in, index_.metric(w) + deficit),
             Confusion::Before::kDoorSeen);
    }
  }
}

void BayesLocalizer::ClearLeafPhases() {
  for (auto* v : {&s1_, &s2_, &t_, &h_}) std::fill(v->begin(), v->end(), 0.0);
}

double BayesLocalizer::Mass(int s) const {
  return n_[s] + i1_[s] + i2_[s] + s1_[s] + s2_[s] + t_[s] + h_[s];
}

void BayesLocalizer::NextWallOverMissedDoors(int n1, int dir, double pn, double angle,
                                             const map::SensedEdge& e, Confusion::Before before) {
  // One sensed wall over missed doors on a flat wall: wall, door, wall, ...
  RunOnOverMissedDoors(n1, dir, index_.metric(n1), pn * angle, 1.0 - FalseDoorAt(n1, before), 0.0,
                       e, before);
}

void BayesLocalizer::RunOnOverMissedDoors(int from, int dir, double total, double mass, double p,
                                          double extra_var, const map::SensedEdge& e,
                                          Confusion::Before first) {
  int cur = from, d = -1, w = -1;
  for (int m = 0; m < model_.settings.max_missed_doors && FlatDoorThenWall(cur, dir, &d, &w); ++m) {
    const double before_w = total + index_.metric(d);
    const double len_w = index_.metric(w);
    const double pf = FalseDoorAt(w, Confusion::Before::kDoorMissed);
    const double missed = MissedAfter(cur, d, m == 0 ? first : Confusion::Before::kDoorMissed);
    // ... ending in the first part of a wall that holds a false door. A false door just past
    // the missed door leaves a first part of a few inches, which the odometry and jamb noise
    // may read as less than nothing: within two of the wall's sigmas it is taken as none.
    const double slack = model_.settings.first_part_in_noise
                             ? 2.0 * std::max(1.0, model_.noise.WallSigmaIn(before_w))
                             : 0.0;
    if (e.metric_in > before_w - slack && e.metric_in <= before_w + len_w) {
      AddFirstPart(State(w, dir), mass * p * missed * pf, std::max(0.0, e.metric_in - before_w));
    }
    total = before_w + len_w;
    p *= missed * (1.0 - pf);
    AddEnd(State(w, dir), mass * p * WallDensityOverMissed(e.metric_in, total, m + 1, extra_var),
           Confusion::Before::kDoorMissed);
    cur = w;
  }
}

void BayesLocalizer::AddFirstPart(int sw, double mass, double w1_in) {
  const double len = index_.metric(sw / 2);
  const double add = mass / len * RoomForFalseDoor(len, w1_in);
  if (add > ni1_[sw]) {
    nc1_[sw] = w1_in;
    nlb1_[sw] = 0;
    nfd1_[sw] = 0;
  }
  ni1_[sw] += add;
}

bool BayesLocalizer::FlatDoorThenWall(int cur, int dir, int* door, int* wall) const {
  const int d = index_.Step(cur, dir);
  if (d < 0 || !map::IsDoorCode(index_.code(d))) return false;
  const int w = index_.Step(d, dir);
  if (w < 0 || index_.code(w) != map::kWallCode) return false;
  const double a_in = dir > 0 ? index_.angle_start(d) : index_.angle_end(d);
  const double a_out = dir > 0 ? index_.angle_start(w) : index_.angle_end(w);
  if (!Coplanar(a_in) || !Coplanar(a_out)) return false;
  *door = d;
  *wall = w;
  return true;
}

void BayesLocalizer::NextSecondPartOverMissedDoors(int s, double p2, double angle,
                                                   const map::SensedEdge& e) {
  if (!model_.settings.w2_over_missed_doors) return;
  const int dir = s % 2 == 0 ? +1 : -1;
  // As SecondPartDensity: the false door's two jambs and its width land on the merged wall.
  double rest = std::max(0.0, index_.metric(s / 2) - c2_[s]);
  double var = FalseDoorVar(s);
  if (lb2_[s]) {
    // Where W2 begins is known only from below (a first edge seen in part): W2 is anywhere
    // up to the rest, taken as normal with the uniform's mean and variance.
    var += rest * rest / 12.0;
    rest *= 0.5;
  }
  RunOnOverMissedDoors(s / 2, dir, rest, p2 * angle, 1.0, var, e);
}

void BayesLocalizer::NextFromFirstPart(int s, double p1, const map::SensedEdge& e) {
  const double eps = model_.settings.outlier;
  const bool door = map::IsDoorCode(e.code);
  const double unit = door ? 1.0 : 1.0 / kOutlierSpanIn;
  nn_[s] += p1 * eps * unit;
  if (door) {
    // The false door that ended W1.
    const double w = e.metric_in > 0.0 ? e.metric_in : ClassWidth(e.code);
    const double angle = std::isnan(e.angle_deg) || Coplanar(e.angle_deg) ? 1.0 : eps;
    ni2_[s] += p1 * angle * model_.confusion.false_class[e.code - 1] * FalseDoorFits(s, w);
    nc2_[s] = c1_[s] + w;
    nc1_[s] = c1_[s];  // I1 and I2 of one wall never hold mass at the same step
    nlb2_[s] = lb1_[s];
    nfd2_[s] = static_cast<std::uint8_t>(std::min(255, fd1_[s] + 1));
  }
}

void BayesLocalizer::NextFromSecondPart(int s, double p2, const map::SensedEdge& e) {
  const double eps = model_.settings.outlier;
  const bool door = map::IsDoorCode(e.code);
  const double unit = door ? 1.0 : 1.0 / kOutlierSpanIn;
  nn_[s] += p2 * eps * unit;
  if (e.code != map::kWallCode) return;
  const double angle = std::isnan(e.angle_deg) || Coplanar(e.angle_deg) ? 1.0 : eps;
  const Confusion& cf = model_.confusion;
  const int wall = s / 2;
  NextSecondPartOverMissedDoors(s, p2, angle, e);
  if (!cf.AnotherFalseDoor(fd2_[s]) || index_.in_row(wall)) {
    nn_[s] += p2 * angle * SecondPartDensity(s, e);
    return;
  }
  // The per-inch model: the rest of the wall past the false door holds no other (the wall
  // ends here) or another (W1 of the rest, anywhere in it, as in NextWallFromEnd), up to
  // the model's most false doors in one wall.
  const double rest = std::max(1.0, index_.metric(wall) - c2_[s]);
  const double pf = cf.FalseDoorIn(rest, false);
  nn_[s] += p2 * angle * (1.0 - pf) * SecondPartDensity(s, e);
  if (e.metric_in <= rest) {
    const double add = p2 * angle * pf / rest * RoomForFalseDoor(rest, e.metric_in);
    if (add > ni1_[s]) {
      nc1_[s] = c2_[s] + e.metric_in;
      nlb1_[s] = lb2_[s];
      nfd1_[s] = fd2_[s];
    }
    ni1_[s] += add;
  }
}

double BayesLocalizer::Fits(double len, double used_in, double width_in) const {
  const SensingNoise& nz = model_.noise;
  const double base = nz.WallSigmaIn(len);
  const double wsig = nz.width_sigma_rel * width_in;
  const double sigma = std::max(
      1.0, std::sqrt(base * base + 2.0 * nz.jamb_sigma_in * nz.jamb_sigma_in + wsig * wsig));
  return 0.5 * std::erfc(-(len - used_in - width_in) / (sigma * std::sqrt(2.0)));
}

double BayesLocalizer::RoomForFalseDoor(double len, double w1_in) const {
  if (!model_.settings.false_door_fit) return 1.0;
  // The narrowest door class: a false door takes at least this much of the wall it is in.
  return Fits(len, w1_in, map::DoorClassWidthIn(map::DoorClass::k30));
}

double BayesLocalizer::FalseDoorFits(int s, double width_in) const {
  if (!model_.settings.false_door_fit) return 1.0;
  return Fits(index_.metric(s / 2), c1_[s], width_in);
}

double BayesLocalizer::SecondPartDensity(int s, const map::SensedEdge& e) const {
  const double len = index_.metric(s / 2);
  const double rest = len - c2_[s];
  if (lb2_[s]) {
    // Only a lower bound of what came before is known: W2 is anywhere up to the rest.
    const double sigma = std::max(1.0, model_.noise.WallSigmaIn(len));
    const double over = std::max(0.0, e.metric_in - rest) / sigma;
    return std::exp(-0.5 * over * over) / len;
  }
  // W1 + ribbon + W2 spans the whole wall: its odometry error, two more jambs and
  // the ribbon's measured width all land on W2.
  return WidenedWallDensity(e.metric_in, rest, len, FalseDoorVar(s));
}

void BayesLocalizer::Normalise() {
  double sum = 0.0;
  for (int s = 0; s < states_; ++s) sum += Mass(s);
  sum += outside_;
  if (!(sum > 0.0) || !std::isfinite(sum)) {
    // Nothing explains the sequence any more (e.g. an open ring ended under every
    // hypothesis): start again from this edge's prior.
    std::fill(n_.begin(), n_.end(), 1.0 / states_);
    std::fill(i1_.begin(), i1_.end(), 0.0);
    std::fill(i2_.begin(), i2_.end(), 0.0);
    ClearLeafPhases();
    ClearPrev();
    outside_ = 0.0;
    sum = 1.0;
  }
  const double inv = 1.0 / sum;
  outside_ *= inv;
  mass_scratch_.assign(states_, 0.0);
  for (int s = 0; s < states_; ++s) {
    for (double* v : {&n_[s], &i1_[s], &i2_[s], &s1_[s], &s2_[s], &t_[s], &h_[s]}) {
      *v *= inv;
      if (*v < kPruneBelow) *v = 0.0;
    }
    mass_scratch_[s] = Mass(s);
  }
  best_ = BestOf(mass_scratch_);
  // The pose is declared once the best place has held the threshold over confirm_edges
  // further edges as well (and confirm_silent_in of silence, UpdateStatus).
  above_ = best_.probability >= model_.settings.threshold ? above_ + 1 : 0;
  silent_in_ = 0.0;
  silence_.clear();
  silence_norm_ = 1.0;
  edge_best_ = best_;
  UpdateStatus();
}

void BayesLocalizer::UpdateStatus() {
  // The silence confirms it, or the next edge did: the place held the threshold over it.
  const bool confirmed = silent_in_ >= model_.settings.confirm_silent_in ||
                         above_ > model_.settings.confirm_edges + 1;
  // Silence only weighs the place the edges put first: it never declares another one.
  const bool held = above_ > model_.settings.confirm_edges && BestIsEdgeBest() &&
                    best_.probability >= model_.settings.threshold && confirmed;
  status_ = held ? RecoveryStatus::kLocalized : RecoveryStatus::kAmbiguous;
}

PoseBelief BayesLocalizer::BestOf(const std::vector<double>& mass) const {
  PoseBelief best;
  for (int s = 0; s < states_; ++s) {
    double p = mass[s];
    if (model_.settings.best_with_neighbours && p > 0.0) {
      // The place is the one of the three with the most belief: a state the belief passes
      // over (a door between two walls it is split on) is not published.
      bool peak = true;
      for (int step : {-1, +1}) {
        const int g = index_.Step(s / 2, step);
        if (g < 0) continue;
        const double q = mass[2 * g + (s & 1)];
        peak = peak && q <= mass[s];
        p += q;
      }
      if (!peak) continue;
    }
    if (p > best.probability) best = PoseBelief{s / 2, (s & 1) ? -1 : +1, p};
  }
  best.probability = std::min(1.0, best.probability);
  return best;
}

bool BayesLocalizer::BestIsEdgeBest() const {
  return best_.edge == edge_best_.edge && best_.dir == edge_best_.dir;
}

void BayesLocalizer::SetSilence(double silent_in) {
  if (edges_ == 0 || states_ == 0) return;
  silent_in_ = std::max(0.0, silent_in);
  silence_.assign(states_, 1.0);
  double sum = outside_;
  for (int s = 0; s < states_; ++s) {
    if (n_[s] > 0.0) silence_[s] = SilenceWeight(s / 2, (s & 1) ? -1 : +1, silent_in_);
    sum += n_[s] * silence_[s] + (Mass(s) - n_[s]);
  }
  silence_norm_ = sum > 0.0 ? 1.0 / sum : 1.0;
  mass_scratch_.assign(states_, 0.0);
  for (int s = 0; s < states_; ++s) mass_scratch_[s] = ViewMass(s);
  best_ = BestOf(mass_scratch_);
  // Silence can withdraw the place the edges put first, never confirm another (UpdateStatus).
  if (!BestIsEdgeBest() || best_.probability < model_.settings.threshold) above_ = 0;
  UpdateStatus();
}

double BayesLocalizer::SilenceWeight(int g, int dir, double silent_in) const {
  // Phi(z): the probability that a sensed end falls at or beyond silent_in.
  const auto beyond = [](double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); };
  const double eps = model_.settings.outlier;
  double start = 0.0, weight = 1.0, survive = 0.0;
  int missed = 0;
  int cur = index_.Step(g, dir);
  while (weight > 0.0) {
    // Off an open ring or out through a corridor's open end: nothing ahead is known.
    if (cur < 0 || index_.open_end(cur)) {
      survive += weight;
      break;
    }
    const double sigma = std::max(1.0, model_.noise.WallSigmaIn(start));
    if (start - silent_in > 4.0 * sigma) {
      survive += weight;  // whatever ends from here on ends beyond the silence
      break;
    }
    if (map::IsDoorCode(index_.code(cur))) {
      // Seen, it ends the sensed wall at its near jamb; missed, the wall runs on over it.
      survive += weight * (1.0 - Missed(cur)) * beyond((start - silent_in) / sigma);
      if (++missed > model_.settings.max_missed_doors) break;
      weight *= Missed(cur);
    } else {
      const int after = index_.Step(cur, dir);
      const double a_out = dir > 0 ? index_.angle_end(cur) : index_.angle_start(cur);
      if (after >= 0 && !index_.open_end(after) && !Coplanar(a_out)) {
        // A corner: the follower turns there.
        const double end = start + index_.metric(cur);
        const double end_sigma = std::max(1.0, model_.noise.WallSigmaIn(end));
        survive += weight * beyond((end - silent_in) / end_sigma);
        break;
      }
    }
    start += index_.metric(cur);
    cur = index_.Step(cur, dir);
  }
  return eps + (1.0 - eps) * survive;
}

double BayesLocalizer::ViewMass(int s) const {
  if (silence_.empty()) return Mass(s);
  return (n_[s] * silence_[s] + (Mass(s) - n_[s])) * silence_norm_;
}

std::vector<PoseBelief> BayesLocalizer::Top(int k) const {
  std::vector<PoseBelief> all;
  if (edges_ == 0) return all;
  for (int s = 0; s < states_; ++s) {
    const double p = ViewMass(s);
    if (p > 0.0) all.push_back({s / 2, (s & 1) ? -1 : +1, p});
  }
  const std::size_t n = std::min<std::size_t>(all.size(), std::max(k, 0));
  std::partial_sort(
      all.begin(), all.begin() + n, all.end(),
      [](const PoseBelief& a, const PoseBelief& b) { return a.probability > b.probability; });
  all.resize(n);
  return all;
}

double BayesLocalizer::PoseProbability(int edge, int dir) const {
  if (edges_ == 0 || edge < 0 || edge >= index_.EdgeCount()) return 0.0;
  return ViewMass(State(edge, dir));
}

}  // namespace stickrep::recovery
