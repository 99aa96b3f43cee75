#include "localizer/localizer.h"

#include <algorithm>
#include <cmath>

#include "common/units.h"

namespace stickrep::localizer {

const char* ToString(Status s) {
  switch (s) {
    case Status::kRecovering: return "RECOVERING";
    case Status::kLocalized: return "LOCALIZED";
    case Status::kLost: return "LOST";
  }
  return "?";
}

Localizer::Localizer(const map::Map& map, LocalizerConfig config)
    : map_(map),
      config_(config),
      index_(map),
      matcher_(index_, config.tolerance),
      assembler_(config.assembler) {
  estimate_.message = "waiting for the first edge";
}

bool Localizer::Advance(double odometer_in) {
  const std::vector<map::SensedEdge> edges = assembler_.Advance(odometer_in);
  if (edges.empty()) {
    if (!estimate_.hypotheses.empty()) Rebuild(odometer_in, estimate_.message);
    return false;
  }
  for (const map::SensedEdge& e : edges) {
    edges_total_++;
    if (matcher_.Extend(e) == 0) {
      // A sensing error: nothing on the map fits. Discard the sequence and start again.
      restarts_++;
      matcher_.Reset();
      assembler_.Restart();
      estimate_ = PoseEstimate{};
      estimate_.status = was_localized_ ? Status::kLost : Status::kRecovering;
      estimate_.message = "no place fits the sensed edges: sequence discarded, starting again";
      was_localized_ = false;
      return true;
    }
  }
  const std::size_t n = matcher_.candidates().size();
  const std::string message = n == 1 ? "one place fits: pose recovered"
                                     : std::to_string(n) + " places fit";
  Rebuild(odometer_in, message);
  return true;
}

void Localizer::Rebuild(double odometer_in, const std::string& message) {
  const auto& cands = matcher_.candidates();
  estimate_.candidates = cands.size();
  estimate_.edges_sensed = matcher_.length();
  estimate_.status = cands.size() == 1 ? Status::kLocalized : Status::kRecovering;
  if (cands.size() == 1) was_localized_ = true;
  estimate_.confidence = cands.empty() ? 0.0 : 1.0 / static_cast<double>(cands.size());
  estimate_.message = message;
  estimate_.hypotheses.clear();
  // How far the robot is past the last matched edge.
  double past_in = 0.0;
  if (assembler_.last_edge_end_in() && assembler_.travel_direction() != 0) {
    past_in = std::max(0.0, assembler_.travel_direction() *
                                (odometer_in - *assembler_.last_edge_end_in()));
  }
  for (std::size_t i = 0; i < cands.size() && static_cast<int>(i) < config_.max_hypotheses; ++i) {
    const map::Candidate& c = cands[i];
    Hypothesis h;
    const int next = index_.Step(c.last, c.dir);
    const int g = next >= 0 ? next : c.last;
    h.ring = index_.RingOf(g);
    h.edge = g - index_.RingOffset(h.ring);
    h.dir = c.dir;
    const map::Ring& ring = map_.ring(h.ring);
    h.offset_in = std::min(past_in, ring.edges[h.edge].metric_in);
    // Node e starts edge e in ring order and carries that edge's heading (gamma).
    const map::Node& start = ring.nodes[h.edge];
    const map::Node& end = ring.nodes[(h.edge + 1) % ring.NodeCount()];
    const double ring_heading = DegToRad(start.gamma_deg);
    const map::Node& from = h.dir > 0 ? start : end;
    h.heading_rad = std::remainder(ring_heading + (h.dir > 0 ? 0.0 : kPi), 2.0 * kPi);
    h.x_in = from.x_in + h.offset_in * std::cos(h.heading_rad);
    h.y_in = from.y_in + h.offset_in * std::sin(h.heading_rad);
    h.probability = estimate_.confidence;
    estimate_.hypotheses.push_back(h);
  }
}

}  // namespace stickrep::localizer
