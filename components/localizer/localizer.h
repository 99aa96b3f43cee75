#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "localizer/edge_assembler.h"
#include "stickrep/map.h"
#include "stickrep/sequence_matcher.h"

namespace stickrep::localizer {

enum class Status { kRecovering, kLocalized, kLost };
const char* ToString(Status s);

// One place the robot may be: just past edge `edge` of ring `ring`, travelling in `dir`.
struct Hypothesis {
  int ring = 0;
  int edge = 0;            // the edge the robot is in now (ring-local index)
  int dir = +1;            // +1: ring order
  double offset_in = 0.0;  // how far into that edge
  double x_in = 0.0, y_in = 0.0, heading_rad = 0.0;  // on the wall, building frame
  double probability = 0.0;
};

struct PoseEstimate {
  Status status = Status::kRecovering;
  std::size_t candidates = 0;
  int edges_sensed = 0;            // in the current sequence
  std::vector<Hypothesis> hypotheses;  // best first; empty while nothing is sensed
  double confidence = 0.0;
  std::string message;
};

struct LocalizerConfig {
  EdgeAssemblerConfig assembler;
  // Metric tolerance of the wall lengths: odometry and jamb placement are not exact.
  map::MatchTolerance tolerance{0.10, 6.0, -1.0};
  int max_hypotheses = 64;
};

// The localizer's logic, free of DDS: door sightings and the odometer in, a pose estimate
// out. Edges are matched incrementally against every ring position in both directions
// (§6.1); when no candidate is left the sequence is discarded and a new one started (the
// deterministic recovery of §6.7); one candidate is the pose.
class Localizer {
 public:
  Localizer(const map::Map& map, LocalizerConfig config = {});

  void AddSighting(const DoorSighting& s) { assembler_.AddSighting(s); }
  // Advances the odometer; true if the estimate changed (new edges were matched).
  bool Advance(double odometer_in);
  const PoseEstimate& estimate() const { return estimate_; }
  std::uint64_t restarts() const { return restarts_; }
  std::uint64_t edges_total() const { return edges_total_; }

 private:
  void Rebuild(double odometer_in, const std::string& message);

  const map::Map& map_;
  LocalizerConfig config_;
  map::MatchIndex index_;
  map::SequenceMatcher matcher_;
  EdgeAssembler assembler_;
  PoseEstimate estimate_;
  std::uint64_t restarts_ = 0;
  std::uint64_t edges_total_ = 0;
  bool was_localized_ = false;
};

}  // namespace stickrep::localizer
