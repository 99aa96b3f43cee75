#pragma once

// What the robot senses on one simulated run (Figure 6.2, steps 0-3, with the error model
// of §6.4.2). The robot starts at a uniformly random point along the walls of the map (a
// random location in the hallway freespace, beside some edge) and travels in a random
// direction. Every true edge it passes is turned into sensed edges:
//
//   door, correct (Table 6.10 true positive)  -> a door of its class, width measured
//   door, mis-sized                           -> a door of another class (missized_to);
//                                                a double door read as one leaf leaves
//                                                the other as the model's leaf reads go
//   door, missed (false negative)             -> wall surface: its width joins the walls
//                                                around it across coplanar (180°) nodes
//   wall, false door (false positive)         -> wall W1, a false door, wall W2, with the
//                                                ribbon at a uniform place in the wall;
//                                                the rate as the Bayes filter weighs it
//                                                (Confusion::FalseDoorIn: per wall or by
//                                                its length, a row's wall by the door
//                                                before it), and with the per-inch model
//                                                W2 may hold another (AnotherFalseDoor)
//   wall or other edge                        -> itself, length measured by odometry
//
// A sensed edge is complete when the robot passes its far end; its sensed boundaries are
// the jambs of sensed doors and every map node between two non-door edges (corners and
// joins: the sonar sees them), so a true wall-wall node is never merged away. Wall lengths
// carry odometry error (a per-run scale error and a random walk, so a wall's error grows
// with its length) plus the placement error of its jambs. The first edge is the one the
// robot starts beside: a door there is seen whole (the camera's 55.8° field covers it from
// the hallway centre), a wall only from the start point on, so its length is a lower bound.
//
// Sensed edges are generated lazily, edge by edge, from one std::mt19937_64, so a run can
// be replayed exactly and read by several matchers.

#include <array>
#include <cstdint>
#include <deque>
#include <random>
#include <vector>

#include "recovery/error_model.h"
#include "stickrep/sequence_matcher.h"

namespace stickrep::recovery {

// Where a run starts: inside global edge `edge` at `offset_in` from its start in the
// direction of travel `dir`.
struct RunStart {
  int edge = 0;
  int dir = +1;
  double offset_in = 0.0;
};

// Uniform along the total length of the edges of `rings` (ring indices of the map; every
// ring when empty), direction uniform. With every ring the draws are those of a map with no
// choice of rings, so a seed starts where it always did.
RunStart DrawStart(const map::MatchIndex& index, std::mt19937_64& rng,
                   const std::vector<int>& rings = {});
// A 64-bit seed for run `run` of trial `trial` of a study seeded with `seed` (splitmix64 of
// the three), so that every run has its own generator whatever the thread that runs it.
std::uint64_t RunSeed(std::uint64_t seed, std::uint64_t trial, std::uint64_t run);

// One sensed edge with its ground truth.
struct StreamEdge {
  map::SensedEdge sensed;
  // The map edge the robot is in when this sensed edge completes (the edge containing its
  // far end); a pose is correct when the single candidate's `last` equals this and its
  // direction is the run's (Figure 6.2, 6.2.2).
  int truth = 0;
  // True travel from the start point to the far end of this edge, inches.
  double end_in = 0.0;
  // An error-free sensing of exactly one map edge: one whole map edge (or the seen part of
  // the first one), the right type and class, and a metric the level-0 matcher accepts.
  bool faithful = true;
  // This wall ends at the near jamb of the sensed door that follows it, so both complete in
  // the same frames and are matched together (a wall's end is only known once the door
  // that ends it has been seen whole).
  bool with_next = false;
};

class SensedStream {
 public:
  // `seed` determines the start and every error of the run. `tolerance` is the level-0
  // tolerance, used only to label edges faithful or not. The run starts beside an edge of
  // `start_rings` (every ring when empty; DrawStart).
  SensedStream(const map::MatchIndex& index, const Confusion& confusion, const SensingNoise& noise,
               const map::MatchTolerance& tolerance, std::uint64_t seed,
               const std::vector<int>& start_rings = {});

  // The i-th sensed edge (0-based), generated on demand; nullptr when the run reached the
  // end of an open ring before it. The edge stays where it is for the stream's lifetime:
  // generating later edges never moves it.
  const StreamEdge* At(int i);
  const RunStart& start() const { return start_; }
  int dir() const { return start_.dir; }

 private:
  // One stretch of surface in travel coordinates, before it becomes a sensed edge.
  struct Piece {
    enum Kind { kSurface, kDoor, kOther } kind = kSurface;
    double a = 0, b = 0;                    // travel coordinates of its ends
    map::SymbolCode code = map::kWallCode;  // sensed code (doors, others)
    double true_width_in = 0;               // doors: the ribbon's true width
    int truth = 0;
    bool error = false;        // made by an injected error (missed, false or mis-sized door)
    bool whole_edge = false;   // exactly one whole map edge
    bool missed_door = false;  // a true door the sensors did not see
    double start_angle = 180;  // sensed angle at its start
    map::DoorMark mark = map::DoorMark::kUnknown;  // doors: the leaf's mark as read
  };
  void ProcessNextTrueEdge();
  // The error model's draws for one true door or wall `p` (a piece of length `len`).
  void SenseDoor(Piece p, map::SymbolCode code, double len);
  void SenseWall(Piece p, double len, Confusion::Before before);
  // A door `p` read mis-sized as one leaf, `deficit` in narrower: the rest of its width as
  // the model's leaf reads go (ErrorModel::leaf_*, weighed by the Bayes filter's leaf
  // phases): a second door, maybe after a sliver of wall; the wall before or after; or
  // nowhere. Only when the model has those reads (LeafReads); else a mis-sized door keeps
  // its walls as they are.
  void SenseLeaf(Piece p, double deficit);
  bool LeafReads() const;
  // The false door of class `false_class`, width_in wide, at_in into wall `p`: adds W1 and
  // the door, and gives back W2, the rest of the wall.
  Piece SplitByFalseDoor(const Piece& p, int false_class, double width_in, double at_in);
  void AddPiece(const Piece& p);
  void FlushRun(bool door_follows);
  void EmitDoor(const Piece& p);
  double MeasureLength(double true_len, int jambs);
  double MeasureWidth(double true_width, map::DoorClass sensed_class);
  // Own samplers on the raw generator: the std:: distributions differ between standard
  // libraries, and runs must replay the same everywhere.
  double Uniform() { return static_cast<double>(rng_() >> 11) * 0x1.0p-53; }
  double Gauss();
  // An index drawn from the distribution p (the last positive entry if p sums short).
  template <std::size_t N>
  int Draw(const std::array<double, N>& p) {
    double u = Uniform();
    int last = 0;
    for (int k = 0; k < static_cast<int>(N); ++k) {
      if (p[k] <= 0.0) continue;
      last = k;
      if (u < p[k]) return k;
      u -= p[k];
    }
    return last;
  }
  int DrawClass(const ClassVector& p) { return Draw(p); }
  // The mark a door's leaf is read as: of map edge `truth`'s mark, read with its class or
  // mis-sized (Confusion::mark_read, mark_read_missized, as the Bayes filter weighs them),
  // or of a false door's (truth < 0); kUnknown without a draw when the model has no marks.
  map::DoorMark DrawMark(int truth, bool class_right = true);

  const map::MatchIndex& index_;
  const Confusion& confusion_;
  const SensingNoise& noise_;
  map::MatchTolerance tolerance_;
  std::mt19937_64 rng_;
  RunStart start_;
  double scale_error_ = 0.0;  // per-run odometry scale error

  int next_edge_ = 0;      // next true edge to process (-1: open ring ended)
  double next_pos_ = 0.0;  // travel coordinate of its start
  // How the true edge just processed was read, when it was a door (a row wall's false-door
  // rate depends on it); kUnknown after any other edge.
  Confusion::Before before_ = Confusion::Before::kUnknown;
  // The door before the short wall of a row sensed last (kUnknown after any other edge).
  Confusion::Before row_door_before_ = Confusion::Before::kUnknown;
  double leaf_to_next_in_ = 0.0;  // a leaf's width the next true edge, a wall, begins with
  bool ended_ = false;
  // The wall surface being accumulated into one sensed wall.
  bool run_active_ = false;
  Piece run_;  // a, start_angle, code of the run; b and truth of its end
  int run_pieces_ = 0;
  bool run_error_ = false;
  bool run_whole_ = false;  // one whole map edge (or the seen part of the first one)
  bool run_lower_bound_ = false;
  bool run_last_missed_ = false;  // its newest piece is a missed door
  int run_missed_ = 0;            // missed doors it runs over
  bool first_emitted_ = false;
  // A deque: At() hands out pointers that later edges must not invalidate.
  std::deque<StreamEdge> edges_;
};

}  // namespace stickrep::recovery
