#pragma once

// The probabilistic matcher (SPEC §5): a discrete Bayes filter over where the robot is on
// the map — (map edge, direction of travel) — that explains the sensed sequence with the
// error model instead of throwing it away when it stops matching exactly.
//
// It is a pair-HMM between the sensed sequence and the map (a profile alignment): the
// hidden state after each sensed edge is the map edge in which that sensed edge ended, in
// one of three phases:
//   N(g)   at the far end of map edge g (the sensed edge ended at a real node or jamb)
//   I1(g)  inside wall g, just before a false door: the sensed wall was the first part W1
//   I2(g)  inside wall g, just after a false door
// From N(g) the next sensed edge is explained by the map edges ahead:
//   wall of length m   the next wall (no false door in it), Gaussian odometry error; or
//                      that wall, a missed door and the wall after it, as one merged wall
//                      (up to max_missed_doors doors); or the first part W1 of a wall that
//                      holds a false door (-> I1, uniform over the wall)
//   door of class c    the next door of class k with P(c | k): Table 6.10's correct or
//                      mis-sized rates and the mis-sized class distribution
//   anything           with a small outlier probability, whatever the next edge is
// From I1 a door is the false door (its class from the false-door distribution) -> I2; from
// I2 a wall is the rest of the wall, W2 = L - W1 - door width, or that rest, a missed door
// and the wall after it as one merged wall (-> N, or -> I1 of that wall before another
// false door).
// A door read at least kLeafDeficitIn narrower than it is (a double door's one leaf)
// leaves the rest of its width somewhere (ErrorModel::leaf_*), in four more phases:
//   S1(d)  the first leaf of door d was sensed; the other leaf comes as a second door,
//   S2(d)  maybe after a sliver of wall (the meeting stiles) between the two;
//   T(d)   door d was sensed as one leaf and the next sensed wall holds the other;
//   H(d)   the sensed wall before door d held its first leaf; the door sensed next is the
//          other leaf.
// Adjacency angles, when sensed, must agree with the map node. Belief that reaches a
// corridor's open end (map::IsOpenEnd) leaves the ring there and starts again from the
// prior (the wall sensed last before it may run on out through it, as far as the next thing
// seen). The first sensed edge is weighed by a prior uniform along the walls (a wall start is the
// part seen from the start point: any wall at least that long). After each edge the belief is
// normalised; a pose is reported when the best (edge, direction) holds at least `threshold` of the
// posterior.

#include <cstdint>
#include <limits>
#include <vector>

#include "recovery/error_model.h"
#include "recovery/pose_recovery.h"
#include "stickrep/sequence_matcher.h"

namespace stickrep::recovery {

// The observation model: the confusion of the landmark pipeline and the metric noise.
struct BayesModel {
  Confusion confusion;
  SensingNoise noise;
  BayesSettings settings;
};

struct PoseBelief {
  int edge = -1;  // global map edge (MatchIndex numbering); -1 before any edge
  int dir = +1;
  double probability = 0.0;
};

class BayesLocalizer {
 public:
  BayesLocalizer(const map::MatchIndex& index, BayesModel model);

  // Incorporates the next sensed edge. Invalid edges (CheckSensedEdge) are counted and
  // ignored. Returns kEmpty before the first edge, then kLocalized or kAmbiguous (never
  // kFailed: an unexplained edge costs probability, it does not end the attempt).
  RecoveryStatus Add(const map::SensedEdge& edge);
  void Reset();
  // The robot reversed its travel (a hallway end, a goal behind) inside the edge after the
  // last sensed one: the belief is carried over instead of being thrown away. A place
  // (g, dir) becomes (next edge, -dir): travelling back, the robot re-enters the part of
  // the next edge it has seen and reaches that edge's far end in the new direction. The
  // first sensed edge after the reversal, when it is a partial wall (that part seen
  // again, metric_is_lower_bound), is consumed without weighing it.
  // `travelled_in`, when known, is how far the robot went past the last sensed edge before
  // it turned back: it may have passed further edges unseen (missed doors along a wall),
  // and the place it turned in is weighed by that distance (ReverseAfter).
  void Reverse(double travelled_in = std::numeric_limits<double>::quiet_NaN());

  // The robot is `silent_in` past the far end of the last sensed edge and the pipeline has
  // sensed nothing over that stretch. Each place is weighed by the probability that the
  // edge it expects next, as sensed, ends that far away or further: every door before was
  // missed, the odometer read long, or the place is wrong (outlier). A place that expected
  // a door or a corner well inside the stretch loses its belief. This is a view: best(),
  // Top(), PoseProbability() and status() give the weighed belief until the next Add(),
  // Reverse() or Reset(), which weighs the edge that ends the silence as usual.
  void SetSilence(double silent_in);
  double silent_in() const { return silent_in_; }

  RecoveryStatus status() const { return status_; }
  // The most probable (edge, direction) and its posterior.
  const PoseBelief& best() const { return best_; }
  // The k most probable poses, best first.
  std::vector<PoseBelief> Top(int k) const;
  double PoseProbability(int edge, int dir) const;
  int edges() const { return edges_; }
  std::uint64_t rejected() const { return rejected_; }
  const BayesModel& model() const { return model_; }
  // The share of the belief that starts again from the prior before each edge
  // (BayesSettings::kidnap_per_edge): a localizer turns it on while it holds a pose and off
  // while it recovers one (a share held back caps the posterior below 1 - share).
  void SetKidnapShare(double share) { model_.settings.kidnap_per_edge = share; }
  // The direction along the rings the robot travels in, when it knows it (+1: ring order,
  // -1: against it, 0: either). Belief that starts from the prior (the first edge, a
  // corridor's open end, the kidnap share) goes to that direction alone; belief already held
  // keeps its direction (Reverse turns it).
  void SetTravelDirection(int ring_dir) { prior_dir_ = ring_dir > 0 ? +1 : ring_dir < 0 ? -1 : 0; }

 private:
  static int State(int g, int dir) { return 2 * g + (dir > 0 ? 0 : 1); }
  double AngleFactor(int g, int dir, const map::SensedEdge& e) const;
  double WallDensity(double measured, double true_len) const;
  // A sensed wall over `missed` missed doors whose true edges add up to `true_len`:
  // WallDensity, shifted and widened by the model's wall_over_missed_door per missed door
  // and widened by `extra_var` (in^2) more.
  double WallDensityOverMissed(double measured, double true_len, int missed,
                               double extra_var) const;
  // A normal density about `mean` whose variance is a wall of `len_in`'s
  // (SensingNoise::WallSigmaIn) plus `extra_var` (in^2).
  double WidenedWallDensity(double measured, double mean, double len_in, double extra_var) const;
  // The variance a false door of leaf state `s` adds to the wall it splits: its two jambs and
  // its measured width (in^2).
  double FalseDoorVar(int s) const;
  // The probability that map door `door` is missed (its class's rate).
  double Missed(int door) const;
  // Whether door `door` after map wall `wall` is read by the door before that wall: both in
  // a row and the model rates a row's doors so (Confusion::RowMissed).
  bool RowLinked(int wall, int door) const;
  // Door `door` after wall `wall` (travelling on from it), the door before the wall
  // `before`: its missed rate, and the factor its read rates take (1 when not row-linked).
  double MissedAfter(int wall, int door, Confusion::Before before) const;
  double ReadFactorAfter(int wall, int door, Confusion::Before before) const;
  // One of the two for the door after N of state `from` (a wall), mixed over the door before
  // that wall as that state's belief passed it (prev_seen_, prev_missed_).
  using RowRate = double (BayesLocalizer::*)(int, int, Confusion::Before) const;
  double MixedFrom(int from, int door, RowRate rate) const;
  // Adds `mass` to N of state s for the next step, the door before its edge `before`.
  void AddEnd(int s, double mass, Confusion::Before before);
  void ClearPrev();
  // The false-door rate of map wall `wall` (in a row of doors or not; by its length where
  // the model rates false doors per inch; in a row, by the door before it where the model
  // rates that: Confusion::FalseDoorIn).
  double FalseDoorAt(int wall, Confusion::Before before = Confusion::Before::kUnknown) const;
  void First(const map::SensedEdge& e);
  // Weighs the belief after a sensed door by how its leaf's mark was read at each map edge
  // (Confusion::MarkLikelihood); nothing when the model has no marks.
  void WeighMark(const map::SensedEdge& e);
  // Adds `weight` times the belief a first sensed edge `e` gives (a start anywhere).
  void AddPrior(const map::SensedEdge& e, double weight);
  // AddPrior()'s share for a partial wall `e` seen in wall g that began earlier, behind g
  // in direction `dir`, and ran over missed doors into g: the start lies in the missed door
  // or the wall behind it that puts the wall's end where it was sensed, at g's end (`end`)
  // or in g's first part before a false door (`first_part`, whose W1 is at least
  // `w1_min_in`). A start is uniform along the walls, so each element the start may lie in
  // gives the density of the sensed length its share of the map's length.
  struct ChainedPrior {
    double end = 0.0;
    double first_part = 0.0;
    double w1_min_in = 0.0;
  };
  ChainedPrior PriorOverMissedDoors(int g, int dir, double sigma, const map::SensedEdge& e) const;
  void Next(const map::SensedEdge& e);
  // Next() for the mass of one state, phase by phase: from N(g), from I1(s), from I2(s).
  // NextFromEnd adds the mass that leaves the ring through an open end to `leaving`.
  void NextFromEnd(int g, int dir, double pn, const map::SensedEdge& e, double* leaving);
  // `before`: what the path passed just before wall n1 (a door seen, or unknown).
  void NextWallFromEnd(int n1, int dir, double pn, double angle, const map::SensedEdge& e,
                       Confusion::Before before);
  void NextWallOverMissedDoors(int n1, int dir, double pn, double angle, const map::SensedEdge& e,
                               Confusion::Before before);
  // The leaf phases: a door sensed as one leaf of door n1 from N(g), the wall before a
  // door n2 that held its first leaf, and the edges sensed in S1, S2, T and H.
  void NextLeafFromEnd(int n1, int dir, double pn, double angle, const map::SensedEdge& e);
  void NextWallBeforeLeaf(int n1, int dir, double pn, double angle, const map::SensedEdge& e,
                          Confusion::Before before);
  void NextFromLeafPhases(int s, const map::SensedEdge& e);
  // The probability that map door `door` (class k) is read as class c, one leaf of it (0
  // when c is not kLeafDeficitIn narrower), and the rest of its width then.
  double LeafRead(int door, int c) const;
  static double LeafDeficit(int k, int c);
  // For H(d): the weight of the wall sensed before d (length `wall_in`, the map's `len`)
  // having held a leaf of class c of door d, summed over c when c < 0.
  double LeafWallWeight(int door, int c, double wall_in, double len) const;
  void NextFromFirstPart(int s, double p1, const map::SensedEdge& e);
  // W2 after a false door: the wall ends there, or (the per-inch model) the rest of the wall
  // holds another false door and the sensed wall is its W1.
  void NextFromSecondPart(int s, double p2, const map::SensedEdge& e);
  // W2 run on over missed doors on a flat wall: the rest of the wall of state s, a missed
  // door, the wall after it (up to max_missed_doors), ending at that wall's end or in its
  // first part before another false door (-> I1). Where the pipeline misses the doors of a
  // row it reads the panels between their casings as doors: rest, missed door, first part,
  // false door, and again.
  void NextSecondPartOverMissedDoors(int s, double p2, double angle, const map::SensedEdge& e);
  // The walk both share: from edge `from` (`total` inches of it sensed so far, its share `p`
  // of `mass` so far) over a missed door and the wall after it, up to max_missed_doors, the
  // sensed wall ending at that wall's end (normal about the length, with `extra_var` more
  // variance than WallDensity's) or in its first part before a false door (-> I1).
  // `first`: the door before wall `from`, for the first door missed after it.
  void RunOnOverMissedDoors(int from, int dir, double total, double mass, double p,
                            double extra_var, const map::SensedEdge& e,
                            Confusion::Before first = Confusion::Before::kUnknown);
  // Adds `mass` to I1 of state sw: the sensed wall was the first part (`w1_in` long) of its
  // wall, before a false door (uniform over the wall, RoomForFalseDoor).
  void AddFirstPart(int sw, double mass, double w1_in);
  // The map door after edge `cur` in direction `dir` and the wall after it, both on a flat
  // wall (coplanar nodes); false when there are none.
  bool FlatDoorThenWall(int cur, int dir, int* door, int* wall) const;
  // A wall's first part W1 is taken uniform over the whole wall; the ribbon of a false door
  // after it must still lie inside the wall. Without that, a wall sensed whole followed by a
  // door leaves belief on "a false door inside the wall just sensed" until the next wall
  // disproves it, a share made again at every door that caps the posterior of a right place.
  // Fits: the probability that `width_in` more fits in a wall `len` long after `used_in`
  // (the rest is not negative beyond the odometry and jamb noise). RoomForFalseDoor: after
  // W1 there is room for the narrowest door. FalseDoorFits: the false door sensed after W1
  // of state s fits in the rest of its wall. Both are 1 unless settings.false_door_fit.
  double Fits(double len, double used_in, double width_in) const;
  double RoomForFalseDoor(double len, double w1_in) const;
  double FalseDoorFits(int s, double width_in) const;
  // The density of the wall `e` as W2, the rest of the wall of state s after its false door.
  double SecondPartDensity(int s, const map::SensedEdge& e) const;
  void Normalise();
  void ClearLeafPhases();
  // The belief of state s over all its phases.
  double Mass(int s) const;
  // Mass(s) as SetSilence() weighs it, normalised.
  double ViewMass(int s) const;
  // The best place from one mass per state (best_with_neighbours: summed with the ring
  // neighbours'); uses mass_scratch_.
  PoseBelief BestOf(const std::vector<double>& mass) const;
  // The probability that the edge after N(g), travelling dir, is sensed to end at least
  // silent_in past g's far end (SetSilence).
  double SilenceWeight(int g, int dir, double silent_in) const;
  void UpdateStatus();
  // The best place is the one the last edge put first (the silence has not moved it).
  bool BestIsEdgeBest() const;
  // Reverse() of the mass at (the last sensed edge before `first`, dir), travelled_in into
  // `first` and beyond: into nn_.
  void ReverseAfter(int first, int dir, double mass, double travelled_in);

  const map::MatchIndex& index_;
  BayesModel model_;
  int states_ = 0;
  double total_length_in_ = 0.0;
  std::vector<double> n_, i1_, i2_;                 // belief per phase and state
  std::vector<double> c1_, c2_;                     // consumed length of the wall in I1 / I2
  std::vector<std::uint8_t> lb1_, lb2_;             // consumed length is only a lower bound
  std::vector<double> nn_, ni1_, ni2_, nc1_, nc2_;  // scratch for the next step
  std::vector<std::uint8_t> nlb1_, nlb2_;
  // False doors the wall held before its part in I1 / I2 (Confusion::AnotherFalseDoor).
  std::vector<std::uint8_t> fd1_, fd2_, nfd1_, nfd2_;
  std::vector<double> s1_, s2_, t_, h_, ns1_, ns2_, nt_, nh_;  // the leaf phases
  // The door before the edge of each N phase, where a row's doors are read by it: the shares
  // of n_[s] that passed it seen and missed (the rest: not known); nseen_, nmissed_ are the
  // masses the next step adds (AddEnd).
  std::vector<double> prev_seen_, prev_missed_, nseen_, nmissed_;
  map::SensedEdge last_;  // the edge sensed last (what T and H need of it)
  RecoveryStatus status_ = RecoveryStatus::kEmpty;
  PoseBelief best_;
  int above_ = 0;  // consecutive edges the best place held the threshold
  double silent_in_ = 0.0;
  std::vector<double> mass_scratch_;  // one mass per state, for BestOf
  PoseBelief edge_best_;         // best() after the last edge, before any silence
  std::vector<double> silence_;  // SilenceWeight of each state's N phase; empty: none
  double silence_norm_ = 1.0;
  bool skip_partial_ = false;  // after Reverse(): the re-seen partial edge is not evidence
  int prior_dir_ = 0;          // SetTravelDirection
  // Belief that left the map's rings through an open end with the last sensed wall: it
  // starts again from the prior at the next edge.
  double outside_ = 0.0;
  int edges_ = 0;
  std::uint64_t rejected_ = 0;
};

}  // namespace stickrep::recovery
