#include "stickrep/ambiguity.h"

#include <algorithm>

namespace stickrep::map {

AmbiguityResult AnalyseAmbiguity(const Map& map, const AmbiguityOptions& options) {
  const MatchIndex index(map);
  MatchTolerance tolerance = options.tolerance;
  if (!options.use_angles) tolerance.angle_deg = -1.0;
  SequenceMatcher matcher(index, tolerance);

  AmbiguityResult out;
  double total_metric = 0;
  for (int g = 0; g < index.EdgeCount(); ++g) total_metric += index.metric(g);
  out.mean_edge_metric_in = index.EdgeCount() > 0 ? total_metric / index.EdgeCount() : 0.0;

  double sum_edges = 0, sum_weighted = 0, sum_weights = 0, sum_distance = 0;
  for (int r = 0; r < index.RingCount(); ++r) {
    // Two periodic sequences that agree on p + q symbols agree forever (Fine and Wilf), so a
    // start still ambiguous after this many edges of a closed ring never becomes unique.
    const int cap = index.RingSize(r) + index.MaxRingSize() + 2;
    for (int i = 0; i < index.RingSize(r); ++i) {
      for (const int dir : {+1, -1}) {
        StartResult s;
        s.start = Cursor{r, i, dir};
        const int first = index.Global(r, i);
        s.first_metric_in = index.metric(first);
        matcher.Reset();
        int g = first;
        while (true) {
          SensedEdge e;
          e.code = index.code(g);
          e.metric_in = index.metric(g);
          if (s.edges == 0) {
            if (options.partial_first_edge) {
              e.metric_in = 0.0;
              e.metric_is_lower_bound = true;
            }
          } else {
            e.angle_deg = dir > 0 ? index.angle_start(g) : index.angle_end(g);
          }
          const std::size_t n = matcher.Extend(e);
          ++s.edges;
          s.distance_in += index.metric(g);
          s.candidates = static_cast<int>(n);
          if (n <= 1) {
            s.outcome = StartOutcome::kUnique;
            break;
          }
          g = index.Step(g, dir);
          if (g < 0) {
            s.outcome = StartOutcome::kRingEnd;
            break;
          }
          if (s.edges >= cap) {
            s.outcome = StartOutcome::kNeverUnique;
            break;
          }
        }
        switch (s.outcome) {
          case StartOutcome::kUnique:
            ++out.unique;
            sum_edges += s.edges;
            sum_weighted += s.edges * s.first_metric_in;
            sum_weights += s.first_metric_in;
            sum_distance += s.distance_in;
            out.max_edges = std::max(out.max_edges, s.edges);
            break;
          case StartOutcome::kRingEnd:
            ++out.ring_end;
            break;
          case StartOutcome::kNeverUnique:
            ++out.never_unique;
            break;
        }
        out.starts.push_back(s);
      }
    }
  }
  if (out.unique > 0) {
    out.mean_edges = sum_edges / out.unique;
    out.mean_distance_in = sum_distance / out.unique;
    out.length_weighted_mean_edges = sum_weighted / sum_weights;
  }
  return out;
}

}  // namespace stickrep::map
