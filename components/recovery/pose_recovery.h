#pragma once

// Pose recovery from a sensed sequence of edges with the error-recovery strategies of
// §6.5–§6.7. Feed one sensed edge at a time; the status says whether the sequence matches
// no place, several, or one (the pose). When a new edge leaves no candidate, a sensing
// error has occurred and the strategy decides what happens:
//
//   kNone           no recovery: the attempt fails (Table 6.11)
//   kRelaxation     stepped metric relaxation 0 -> 10 -> 20 % -> fail (Figure 6.4), walls
//                   and door widths together
//   kFirstFrame     discard the sequence and start a new one if the failure came in the
//                   first frame (§6.6.1, Table 6.12); otherwise fail
//   kFalseDoor      remove doors of the least likely class, newest first, re-matching after
//                   each removal (§6.6.2, Table 6.13)
//   kMissized       relax door widths only, 10 then 20 % (§6.6.3, Table 6.14)
//   kFullSuite      first frame, then for each relaxation level (walls and doors) a
//                   re-match and the false-door removal (§6.6.4, Table 6.15)
//   kDeterministic  discard the whole sequence and start a new one (§6.7, Table 6.16)
//
// Independent of the simulation study: the localizer feeds it edges from its assembler.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "recovery/error_model.h"
#include "recovery/relaxed_matcher.h"
#include "stickrep/sequence_matcher.h"

namespace stickrep::recovery {

enum class Strategy {
  kNone,
  kRelaxation,
  kFirstFrame,
  kFalseDoor,
  kMissized,
  kFullSuite,
  kDeterministic
};
inline constexpr Strategy kAllStrategies[] = {
    Strategy::kNone,     Strategy::kRelaxation, Strategy::kFirstFrame,   Strategy::kFalseDoor,
    Strategy::kMissized, Strategy::kFullSuite,  Strategy::kDeterministic};
// "none", "relaxation", "first-frame", "false-door", "missized", "full-suite",
// "deterministic".
const char* StrategyName(Strategy s);
std::optional<Strategy> ParseStrategy(std::string_view name);

enum class RecoveryStatus {
  kEmpty,      // nothing sensed in the current sequence (start, or just restarted)
  kAmbiguous,  // several candidates: keep travelling
  kLocalized,  // one candidate: the pose
  kFailed,     // no candidate and the strategy could not recover; Reset() to start again
};
const char* StatusName(RecoveryStatus s);

// What the last Add() did.
enum class RecoveryEvent {
  kExtended,      // the edge extended the surviving candidates
  kRejected,      // the edge was invalid and ignored (see CheckSensedEdge)
  kRestarted,     // the sequence was discarded; a new one starts with the next edge
  kRelaxed,       // re-matched at a higher relaxation level
  kDoorsRemoved,  // re-matched after removing suspected false doors
  kFailed,        // the strategy gave up
};

struct RecoveryConfig {
  Strategy strategy = Strategy::kDeterministic;
  // The level-0 tolerance (what the sensors deliver in the envelope).
  map::MatchTolerance base_tolerance{0.06, 4.0, 20.0};
  std::vector<double> relaxation_steps{0.10, 0.20};  // Figure 6.4
  // A failure while the sequence holds at most this many edges is "in the first frame".
  int first_frame_edges = 2;
  // A priori door-class probabilities for the false-door heuristic; all zero: the map's
  // door-class frequencies.
  ClassVector door_prior{};
  // Deterministic recovery: start the new sequence with the edge that failed instead of
  // discarding it too (the text discards the whole sequence; off by default).
  bool restart_with_failing_edge = false;
  // After a restart the first wall of the new sequence is taken as a lower bound: the
  // failure says some recent boundary was wrong (a false door's jamb, say), so where that
  // wall began is not known — the same as at the start of a run.
  bool restart_wall_is_lower_bound = true;

  static RecoveryConfig For(Strategy strategy, const StudyConfig& study);
};

// Why a sensed edge cannot be used (unknown code, NaN or negative metric, angle out of
// range), or nullopt when it is fine.
std::optional<std::string> CheckSensedEdge(const map::SensedEdge& edge);

class PoseRecovery {
 public:
  PoseRecovery(const map::MatchIndex& index, RecoveryConfig config);

  // Adds the next sensed edge. An invalid edge is counted, ignored and reported as
  // RecoveryEvent::kRejected. After kFailed, edges are ignored until Reset().
  RecoveryStatus Add(const map::SensedEdge& edge) { return AddEdges(&edge, 1); }
  // Adds edges completed together (a wall and the door that ends it are seen in the same
  // frames): all are appended before the sequence is judged, so a recovery sees both.
  RecoveryStatus AddEdges(const map::SensedEdge* edges, std::size_t count);
  // Forgets the sequence and every relaxation; counters are kept.
  void Reset();

  RecoveryStatus status() const { return status_; }
  RecoveryEvent last_event() const { return last_event_; }
  // Candidates of the current sequence: (start edge, direction, edge matched to the newest
  // sensed edge — where the robot is now).
  const std::vector<map::Candidate>& candidates() const { return matcher_.candidates(); }
  // The single candidate when localized.
  std::optional<map::Candidate> pose() const;
  // The current sequence as matched (after any door removals).
  const std::vector<map::SensedEdge>& sequence() const { return sequence_; }
  double wall_relaxation() const { return matcher_.wall_relaxation(); }
  double door_relaxation() const { return matcher_.door_relaxation(); }
  const RecoveryConfig& config() const { return config_; }

  std::uint64_t restarts() const { return restarts_; }
  std::uint64_t removed_doors() const { return removed_doors_; }
  std::uint64_t rejected() const { return rejected_; }
  // Door classes the false-door heuristic removes (zero prior, and the least likely).
  const std::vector<map::SymbolCode>& removable_codes() const { return removable_; }

 private:
  RecoveryStatus StatusFor(std::size_t n) const;
  void SetLevel(int level);  // 0 = base tolerance, i = relaxation_steps[i-1]
  std::size_t Rematch() { return matcher_.MatchAll(sequence_); }
  bool Recover(const map::SensedEdge& failing);
  void Restart(const map::SensedEdge& failing);
  bool TryRaiseLevel(bool walls_too);
  // Sets the relaxation level and matches again: true (and RELAXED) when some place fits.
  bool RematchAtLevel(int level);
  bool TryRemoveDoors();

  RecoveryConfig config_;
  RelaxedMatcher matcher_;
  std::vector<map::SensedEdge> sequence_;
  std::vector<map::SymbolCode> removable_;
  int level_ = 0;
  // After removing a door that was the newest edge, the wall before it is still open: the
  // next sensed wall continues it.
  bool trailing_wall_open_ = false;
  bool trailing_wall_was_lower_bound_ = false;
  bool restarted_ = false;  // the next edge begins a sequence after a restart
  RecoveryStatus status_ = RecoveryStatus::kEmpty;
  RecoveryEvent last_event_ = RecoveryEvent::kExtended;
  std::uint64_t restarts_ = 0;
  std::uint64_t removed_doors_ = 0;
  std::uint64_t rejected_ = 0;
};

}  // namespace stickrep::recovery
