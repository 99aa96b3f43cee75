#include "map_tool/ambiguity_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>

#include "plot/bar_chart.h"
#include "stickrep/paper_reference.h"

namespace stickrep::map {

namespace {

const char* OutcomeName(StartOutcome o) {
  switch (o) {
    case StartOutcome::kUnique:
      return "unique";
    case StartOutcome::kRingEnd:
      return "ring end";
    case StartOutcome::kNeverUnique:
      return "never unique";
  }
  return "?";
}

std::string Semantics(const AmbiguityOptions& o) {
  return fmt::format(
      "first edge {}, walls matched {}, angles {}",
      o.partial_first_edge ? "partly seen (a first wall's length unknown)" : "sensed whole",
      (o.tolerance.metric_rel == 0 && o.tolerance.metric_abs_in == 0)
          ? std::string("exactly")
          : fmt::format("within max({:g} in, {:g} %)", o.tolerance.metric_abs_in,
                        100 * o.tolerance.metric_rel),
      o.use_angles ? "compared" : "ignored");
}

std::map<int, int> Distribution(const AmbiguityResult& r) {
  std::map<int, int> d;
  for (const StartResult& s : r.starts) {
    if (s.outcome == StartOutcome::kUnique) ++d[s.edges];
  }
  return d;
}

std::vector<const StartResult*> Worst(const AmbiguityResult& r, int n) {
  std::vector<const StartResult*> v;
  for (const StartResult& s : r.starts) v.push_back(&s);
  std::stable_sort(v.begin(), v.end(), [](const StartResult* a, const StartResult* b) {
    const bool ua = a->outcome == StartOutcome::kUnique, ub = b->outcome == StartOutcome::kUnique;
    if (ua != ub) return !ua;  // unresolved first
    return a->edges > b->edges;
  });
  if (static_cast<int>(v.size()) > n) v.resize(n);
  return v;
}

}  // namespace

std::string FormatAmbiguityText(const Map& map, const AmbiguityOptions& options,
                                const AmbiguityResult& r, const AmbiguityReportOptions& report) {
  std::string out;
  out += fmt::format("Starting-location ambiguity of {} (Figure 6.1), no sensing error\n",
                     map.info().name);
  out += fmt::format("  semantics: {}\n", Semantics(options));
  out += fmt::format(
      "  starts: {} ({} edges x 2 directions): unique {}, ring end first {}, "
      "never unique {}\n",
      r.starts.size(), r.starts.size() / 2, r.unique, r.ring_end, r.never_unique);
  const double ft = r.mean_edges * r.mean_edge_metric_in / 12.0;
  out += fmt::format(
      "  edges to a unique pose: mean {:.2f} (per start), {:.2f} (starts weighted by the "
      "length of their first edge), max {}\n",
      r.mean_edges, r.length_weighted_mean_edges, r.max_edges);
  out += fmt::format(
      "  distance: {:.2f} ft as the text computes it (mean edges x mean edge metric {:.2f} in), "
      "{:.2f} ft summed over the sensed edges; time at {} ft/s: {:.2f} s\n",
      ft, r.mean_edge_metric_in, r.mean_distance_in / 12.0, paper::kBaseSpeedFtPerS,
      ft / paper::kBaseSpeedFtPerS);
  if (const auto* p = paper::NoErrorFor(map.info().name)) {
    out += fmt::format(
        "  paper (Table 6.22, {}, no error): {:.2f} edges, {:.2f} ft, {:.2f} s; ours - paper = "
        "{:+.2f} edges\n",
        p->label, p->edges, p->distance_ft, p->time_s, r.mean_edges - p->edges);
  }
  if (report.seconds > 0) out += fmt::format("  analysis time: {:.3f} s\n", report.seconds);
  out += "\n  distribution (edges: starts)\n";
  const auto dist = Distribution(r);
  int biggest = 1;
  for (const auto& [k, n] : dist) biggest = std::max(biggest, n);
  for (const auto& [k, n] : dist) {
    out += fmt::format("  {:>5}: {:>5} {}\n", k, n,
                       std::string((n * 50 + biggest - 1) / biggest, '#'));
  }
  out += fmt::format("\n  worst starts (ring, edge, direction)\n");
  for (const StartResult* s : Worst(r, report.worst)) {
    const Ring& ring = map.ring(s->start.ring);
    const Edge& e = ring.edges[s->start.edge];
    out += fmt::format("  {:<24} edge {:>4} ({:<9}) dir {:+d}: {} after {} edges ({} candidates)\n",
                       ring.id, s->start.edge,
                       e.IsDoor() ? std::string("door") + DoorClassName(*e.door_class)
                                  : fmt::format("{} {:g}", EdgeTypeName(e.type), e.metric_in),
                       s->start.dir, OutcomeName(s->outcome), s->edges, s->candidates);
  }
  return out;
}

nlohmann::json AmbiguityJson(const Map& map, const AmbiguityOptions& options,
                             const AmbiguityResult& r, const AmbiguityReportOptions& report) {
  nlohmann::json j;
  j["map"] = map.info().name;
  j["semantics"] = {{"partial_first_edge", options.partial_first_edge},
                    {"use_angles", options.use_angles},
                    {"metric_rel", options.tolerance.metric_rel},
                    {"metric_abs_in", options.tolerance.metric_abs_in}};
  j["starts"] = r.starts.size();
  j["unique"] = r.unique;
  j["ring_end"] = r.ring_end;
  j["never_unique"] = r.never_unique;
  j["mean_edges"] = r.mean_edges;
  j["length_weighted_mean_edges"] = r.length_weighted_mean_edges;
  j["max_edges"] = r.max_edges;
  j["mean_edge_metric_in"] = r.mean_edge_metric_in;
  j["mean_distance_ft"] = r.mean_edges * r.mean_edge_metric_in / 12.0;
  j["mean_sensed_distance_ft"] = r.mean_distance_in / 12.0;
  if (report.seconds > 0) j["analysis_seconds"] = report.seconds;
  if (const auto* p = paper::NoErrorFor(map.info().name)) {
    j["paper"] = {{"edges", p->edges}, {"distance_ft", p->distance_ft}, {"time_s", p->time_s}};
  }
  nlohmann::json dist = nlohmann::json::object();
  for (const auto& [k, n] : Distribution(r)) dist[std::to_string(k)] = n;
  j["distribution"] = dist;
  nlohmann::json worst = nlohmann::json::array();
  for (const StartResult* s : Worst(r, report.worst)) {
    worst.push_back({{"ring", map.ring(s->start.ring).id},
                     {"edge", s->start.edge},
                     {"dir", s->start.dir},
                     {"outcome", OutcomeName(s->outcome)},
                     {"edges", s->edges},
                     {"candidates", s->candidates}});
  }
  j["worst"] = worst;
  return j;
}

void WriteAmbiguityHistogramPng(const Map& map, const AmbiguityResult& r, const std::string& path) {
  std::vector<int> samples;
  for (const StartResult& s : r.starts) {
    if (s.outcome == StartOutcome::kUnique) samples.push_back(s.edges);
  }
  const int hi = std::max(2, r.max_edges);
  const plot::BarChart chart =
      plot::IntegerHistogramOf(samples, 1, hi,
                               fmt::format("{}: edges to a unique pose, no error (mean {:.2f})",
                                           map.info().name, r.mean_edges),
                               "edges sensed", "starts");
  plot::WriteBarChartPng(chart, path);
}

}  // namespace stickrep::map
