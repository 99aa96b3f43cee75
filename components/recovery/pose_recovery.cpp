#include "recovery/pose_recovery.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stickrep::recovery {

using map::SensedEdge;
using map::SymbolCode;

const char* StrategyName(Strategy s) {
  switch (s) {
    case Strategy::kNone:
      return "none";
    case Strategy::kRelaxation:
      return "relaxation";
    case Strategy::kFirstFrame:
      return "first-frame";
    case Strategy::kFalseDoor:
      return "false-door";
    case Strategy::kMissized:
      return "missized";
    case Strategy::kFullSuite:
      return "full-suite";
    case Strategy::kDeterministic:
      return "deterministic";
  }
  return "?";
}

std::optional<Strategy> ParseStrategy(std::string_view name) {
  for (const Strategy s : kAllStrategies) {
    if (name == StrategyName(s)) return s;
  }
  return std::nullopt;
}

const char* StatusName(RecoveryStatus s) {
  switch (s) {
    case RecoveryStatus::kEmpty:
      return "empty";
    case RecoveryStatus::kAmbiguous:
      return "ambiguous";
    case RecoveryStatus::kLocalized:
      return "localized";
    case RecoveryStatus::kFailed:
      return "failed";
  }
  return "?";
}

RecoveryConfig RecoveryConfig::For(Strategy strategy, const StudyConfig& study) {
  RecoveryConfig c;
  c.strategy = strategy;
  c.base_tolerance = study.base_tolerance;
  c.relaxation_steps = study.relaxation_steps;
  c.first_frame_edges = study.first_frame_edges;
  return c;
}

std::optional<std::string> CheckSensedEdge(const SensedEdge& edge) {
  if (edge.code >= map::kSymbolCodeCount) {
    return "unknown edge symbol code " + std::to_string(edge.code);
  }
  if (std::isnan(edge.metric_in)) return "metric is NaN";
  if (!std::isfinite(edge.metric_in)) return "metric is infinite";
  if (edge.metric_in < 0.0) return "metric is negative";
  if (!std::isnan(edge.angle_deg) && !(edge.angle_deg >= 0.0 && edge.angle_deg <= 360.0)) {
    return "angle outside [0, 360] degrees";
  }
  return std::nullopt;
}

PoseRecovery::PoseRecovery(const map::MatchIndex& index, RecoveryConfig config)
    : config_(std::move(config)), matcher_(index, config_.base_tolerance) {
  ClassVector prior = config_.door_prior;
  double sum = 0;
  for (double p : prior) sum += p;
  if (sum <= 0.0) {
    for (int k = 0; k < kDoorClasses; ++k) {
      prior[k] = static_cast<double>(
          index.EdgesWithCode(map::DoorCode(static_cast<map::DoorClass>(k))).size());
    }
  }
  // §6.6.2: the door type whose a priori probability is lowest. A class the map does not
  // have at all is less likely still, so it is removed as well.
  double least = std::numeric_limits<double>::infinity();
  for (double p : prior) {
    if (p > 0.0) least = std::min(least, p);
  }
  for (int k = 0; k < kDoorClasses; ++k) {
    if (prior[k] <= 0.0 || prior[k] == least) {
      removable_.push_back(map::DoorCode(static_cast<map::DoorClass>(k)));
    }
  }
  sequence_.reserve(64);
}

void PoseRecovery::Reset() {
  sequence_.clear();
  SetLevel(0);
  matcher_.Reset();
  trailing_wall_open_ = false;
  restarted_ = false;
  status_ = RecoveryStatus::kEmpty;
  last_event_ = RecoveryEvent::kExtended;
}

std::optional<map::Candidate> PoseRecovery::pose() const {
  if (status_ != RecoveryStatus::kLocalized) return std::nullopt;
  return candidates().front();
}

RecoveryStatus PoseRecovery::StatusFor(std::size_t n) const {
  if (n == 0) return sequence_.empty() ? RecoveryStatus::kEmpty : RecoveryStatus::kFailed;
  return n == 1 ? RecoveryStatus::kLocalized : RecoveryStatus::kAmbiguous;
}

void PoseRecovery::SetLevel(int level) {
  level_ = level;
  const double r = level == 0 ? 0.0 : config_.relaxation_steps[level - 1];
  switch (config_.strategy) {
    case Strategy::kMissized:
      matcher_.SetRelaxation(0.0, r);
      break;
    case Strategy::kRelaxation:
    case Strategy::kFullSuite:
      matcher_.SetRelaxation(r, r);
      break;
    default:
      matcher_.SetRelaxation(0.0, 0.0);
      break;
  }
}

RecoveryStatus PoseRecovery::AddEdges(const SensedEdge* edges, std::size_t count) {
  if (status_ == RecoveryStatus::kFailed) {
    last_event_ = RecoveryEvent::kFailed;
    return status_;
  }
  last_event_ = RecoveryEvent::kExtended;
  std::size_t n = candidates().size();
  const SensedEdge* newest = nullptr;
  for (std::size_t i = 0; i < count; ++i) {
    const SensedEdge& edge = edges[i];
    if (CheckSensedEdge(edge)) {
      ++rejected_;
      continue;
    }
    newest = &edge;
    if (restarted_ && sequence_.empty() && config_.restart_wall_is_lower_bound &&
        map::CodeHasMetric(edge.code)) {
      SensedEdge first = edge;
      first.metric_is_lower_bound = true;
      restarted_ = false;
      sequence_.push_back(first);
      n = matcher_.Extend(first);
      continue;
    }
    restarted_ = false;
    if (trailing_wall_open_ && edge.code == map::kWallCode) {
      // The wall interrupted by a removed door goes on: this is the rest of it.
      SensedEdge& wall = sequence_.back();
      wall.metric_in += edge.metric_in;
      wall.metric_is_lower_bound = trailing_wall_was_lower_bound_ || edge.metric_is_lower_bound;
      trailing_wall_open_ = false;
      n = Rematch();
    } else {
      trailing_wall_open_ = false;
      sequence_.push_back(edge);
      n = matcher_.Extend(edge);
    }
  }
  if (newest == nullptr) {
    last_event_ = RecoveryEvent::kRejected;
    return status_;
  }
  if (n > 0) {
    status_ = StatusFor(n);
    return status_;
  }
  if (!Recover(*newest)) {
    status_ = RecoveryStatus::kFailed;
    last_event_ = RecoveryEvent::kFailed;
  }
  return status_;
}

void PoseRecovery::Restart(const SensedEdge& failing) {
  ++restarts_;
  sequence_.clear();
  SetLevel(0);
  matcher_.Reset();
  trailing_wall_open_ = false;
  status_ = RecoveryStatus::kEmpty;
  last_event_ = RecoveryEvent::kRestarted;
  restarted_ = true;
  if (config_.restart_with_failing_edge) {
    SensedEdge first = failing;
    sequence_.push_back(first);
    const std::size_t n = matcher_.Extend(first);
    if (n == 0) {
      sequence_.clear();
      matcher_.Reset();
    }
    status_ = StatusFor(n);
  }
}

bool PoseRecovery::Recover(const SensedEdge& failing) {
  const bool first_frame = static_cast<int>(sequence_.size()) <= config_.first_frame_edges;
  switch (config_.strategy) {
    case Strategy::kNone:
      return false;
    case Strategy::kDeterministic:
      Restart(failing);
      return true;
    case Strategy::kFirstFrame:
      if (!first_frame) return false;
      Restart(failing);
      return true;
    case Strategy::kRelaxation:
    case Strategy::kMissized:
      return TryRaiseLevel(/*walls_too=*/config_.strategy == Strategy::kRelaxation);
    case Strategy::kFalseDoor:
      return TryRemoveDoors();
    case Strategy::kFullSuite: {
      if (first_frame) {
        Restart(failing);
        return true;
      }
      // At the current level first the doors, then each higher level: re-match, then doors.
      if (TryRemoveDoors()) return true;
      const int levels = static_cast<int>(config_.relaxation_steps.size());
      for (int level = level_ + 1; level <= levels; ++level) {
        if (RematchAtLevel(level) || TryRemoveDoors()) return true;
      }
      return false;
    }
  }
  return false;
}

bool PoseRecovery::TryRaiseLevel(bool walls_too) {
  (void)walls_too;  // SetLevel() knows from the strategy which metrics it relaxes
  const int levels = static_cast<int>(config_.relaxation_steps.size());
  for (int level = level_ + 1; level <= levels; ++level) {
    if (RematchAtLevel(level)) return true;
  }
  return false;
}

bool PoseRecovery::RematchAtLevel(int level) {
  SetLevel(level);
  const std::size_t n = Rematch();
  if (n == 0) return false;
  status_ = StatusFor(n);
  last_event_ = RecoveryEvent::kRelaxed;
  return true;
}

bool PoseRecovery::TryRemoveDoors() {
  auto removable = [&](const SensedEdge& e) {
    return std::find(removable_.begin(), removable_.end(), e.code) != removable_.end();
  };
  std::vector<SensedEdge> work = sequence_;
  bool open = false;         // the newest edge is a wall that is still open
  bool open_was_lb = false;  // whether that wall was a lower bound before it was opened
  int removed = 0;
  for (int i = static_cast<int>(work.size()) - 1; i >= 0; --i) {
    if (i >= static_cast<int>(work.size()) || !removable(work[i])) continue;
    const SensedEdge door = work[i];
    const double width = door.metric_in > 0.0
                             ? door.metric_in
                             : map::DoorClassWidthIn(static_cast<map::DoorClass>(door.code - 1));
    const bool prev_wall = i > 0 && work[i - 1].code == map::kWallCode;
    const bool next_wall =
        i + 1 < static_cast<int>(work.size()) && work[i + 1].code == map::kWallCode;
    const bool last = i + 1 == static_cast<int>(work.size());
    // A false door sat on a wall: the wall surface it covered joins its neighbours.
    if (prev_wall) {
      SensedEdge& w = work[i - 1];
      const bool prev_lb = w.metric_is_lower_bound;
      w.metric_in += width;
      if (next_wall) {
        const SensedEdge& n = work[i + 1];
        w.metric_in += n.metric_in;
        w.metric_is_lower_bound = prev_lb || n.metric_is_lower_bound;
        // If the wall after the door was the open newest edge, the joined wall is open now.
        if (open && i + 2 == static_cast<int>(work.size())) open_was_lb = prev_lb || open_was_lb;
        work.erase(work.begin() + i, work.begin() + i + 2);
      } else {
        work.erase(work.begin() + i);
        if (last) {
          // Removing the newest edge leaves the wall before it unfinished.
          open = true;
          open_was_lb = w.metric_is_lower_bound;
          w.metric_is_lower_bound = true;
        }
      }
    } else if (next_wall) {
      SensedEdge& n = work[i + 1];
      n.metric_in += width;
      n.angle_deg = door.angle_deg;
      if (i == 0) n.metric_is_lower_bound = true;  // where this wall began is unknown now
      work.erase(work.begin() + i);
    } else {
      work.erase(work.begin() + i);
    }
    ++removed;
    if (!work.empty()) work.front().angle_deg = std::numeric_limits<double>::quiet_NaN();
    const std::size_t n = matcher_.MatchAll(work);
    if (n > 0) {
      sequence_ = std::move(work);
      trailing_wall_open_ = open;
      trailing_wall_was_lower_bound_ = open_was_lb;
      removed_doors_ += removed;
      status_ = StatusFor(n);
      last_event_ = RecoveryEvent::kDoorsRemoved;
      return true;
    }
  }
  Rematch();  // back to the unedited sequence (which has no candidate)
  return false;
}

}  // namespace stickrep::recovery
