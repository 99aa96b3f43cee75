#include "study_tool/study_report.h"

#include <fmt/format.h>
#include <fmt/ostream.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <thread>

#include "common/config_paths.h"
#include "common/input_error.h"
#include "plot/bar_chart.h"
#include "stickrep/map_io.h"
#include "stickrep/paper_reference.h"

namespace stickrep::recovery::report {

namespace {

struct PaperEntry {
  const char* map;
  const char* method;
  PaperLines lines;
};

// Tables 6.11–6.21 (§6.5–§6.8), exactly as printed.
constexpr PaperEntry kPaperLines[] = {
    {"engineering_building_3f",
     "none",
     {"6.11", "Performance without heuristics", 43.80, 0.00, 41.70, 57.30, 1.00}},
    {"engineering_building_3f",
     "first-frame",
     {"6.12", "Performance with First Frame Heuristic", 43.30, 15.70, 34.80, 63.50, 1.70}},
    {"engineering_building_3f",
     "false-door",
     {"6.13", "Performance with False Door Heuristic", 43.67, 40.30, 23.40, 74.00, 2.60}},
    {"engineering_building_3f",
     "missized",
     {"6.14", "Performance with Mis-sized Heuristic", 44.30, 28.37, 31.90, 66.90, 1.20}},
    {"engineering_building_3f",
     "full-suite",
     {"6.15", "Performance with Full Heuristic Suite", 42.20, 62.80, 8.20, 84.30, 7.50}},
    {"engineering_building_3f",
     "deterministic",
     {"6.16", "Performance of deterministic recovery in Engineering Building", 41.50, 94.70, 0.00,
      97.80, 2.20}},
    {"wells_hall_7f",
     "deterministic",
     {"6.18", "Performance of deterministic recovery in Wells Hall", 69.70, 90.82, 0.00, 93.60,
      6.40}},
    {"regular_polygon_46",
     "deterministic",
     {"6.19", "Performance of deterministic recovery in regular polygon", 96.00, 97.92, 0.00, 98.00,
      2.00}},
    {"storefront",
     "deterministic",
     {"6.20", "Performance of deterministic recovery along synthetic storefront", 47.40, 93.15,
      0.00, 96.10, 3.90}},
    {"wells_hall_7f_modified",
     "deterministic",
     {"6.21", "Performance of deterministic recovery in a modified Wells Hall", 62.40, 91.35, 0.00,
      94.60, 5.40}},
};

// Table 6.22, modeled error.
struct PaperModeled {
  const char* map;
  PaperSummary s;
};
constexpr PaperModeled kPaperModeled[] = {
    {"engineering_building_3f", {6.84, 38.55, 14.83, 97.8}},
    {"wells_hall_7f", {37.05, 188.96, 72.68, 93.6}},
    {"wells_hall_7f_modified", {14.76, 75.28, 28.95, 94.6}},
    {"regular_polygon_46", {66.62, 555.19, 213.54, 98.0}},
    {"storefront", {18.04, 92.19, 37.88, 96.1}},
};

// The five domains of §6.8 in the order of Table 6.22.
constexpr const char* kSuiteMaps[] = {"engineering_building_3f", "wells_hall_7f",
                                      "wells_hall_7f_modified", "regular_polygon_46", "storefront"};

std::string Paper(std::optional<double> v, int decimals = 2) {
  return v ? fmt::format("{:.{}f}", *v, decimals) : std::string("-");
}

MethodSpec ParseMethod(const std::string& id) {
  MethodSpec m;
  if (id == "no-error") {
    m.error_free = true;
    return m;
  }
  if (id == "bayes") {
    m.kind = MethodSpec::Kind::kBayes;
    return m;
  }
  if (id == "bayes-no-error") {
    m.kind = MethodSpec::Kind::kBayes;
    m.error_free = true;
    return m;
  }
  const auto s = ParseStrategy(id);
  if (!s) {
    throw std::invalid_argument("unknown method '" + id +
                                "' (no-error, none, relaxation, first-frame, false-door, "
                                "missized, full-suite, deterministic, bayes)");
  }
  m.strategy = *s;
  return m;
}

std::vector<int> EdgeCounts(const ExperimentResult& e, int runs) {
  std::vector<int> v;
  const std::size_t off = static_cast<std::size_t>(e.median_trial) * runs;
  for (int i = 0; i < runs; ++i) {
    const RunResult& r = e.runs[off + i];
    if (r.outcome != Outcome::kNotConverged) v.push_back(r.edges);
  }
  return v;
}

nlohmann::json TrialJson(const TrialSummary& t) {
  return {{"runs", t.runs},
          {"pct_with_error", t.pct_with_error},
          {"pct_recovered", t.pct_recovered},
          {"pct_not_converged", t.pct_not_converged},
          {"pct_correct", t.pct_correct},
          {"pct_incorrect", t.pct_incorrect},
          {"mean_edges", t.mean_edges},
          {"mean_distance_ft", t.mean_distance_ft},
          {"mean_time_s", t.mean_time_s},
          {"mean_restarts", t.mean_restarts}};
}

nlohmann::json DomainJson(const DomainResult& d, const StudyOptions& o) {
  nlohmann::json j;
  j["map"] = d.map_name;
  j["label"] = DomainLabel(d.map_name);
  j["map_edges"] = d.map_edges;
  j["mean_edge_metric_in"] = d.mean_edge_metric_in;
  j["start_rings"] = o.start_rings;  // empty: every ring
  j["seconds"] = d.seconds;
  for (const ExperimentResult& e : d.experiments) {
    nlohmann::json x;
    x["method"] = e.method.Id();
    x["median_trial"] = e.median_trial;
    x["median"] = TrialJson(e.median());
    x["all"] = TrialJson(e.all);
    for (const TrialSummary& t : e.trials) x["trials"].push_back(TrialJson(t));
    std::vector<int> hist;
    for (int edges : EdgeCounts(e, o.runs)) {
      if (edges >= static_cast<int>(hist.size())) hist.resize(edges + 1, 0);
      ++hist[edges];
    }
    x["median_trial_edges_histogram"] = hist;  // index = edges sensed
    if (const auto p = PaperLinesFor(d.map_name, e.method.Id())) {
      x["paper"] = {{"table", p->table},
                    {"pct_with_error", p->with_error},
                    {"pct_recovered", p->recovered},
                    {"pct_not_converged", p->not_converged},
                    {"pct_correct", p->correct},
                    {"pct_incorrect", p->incorrect}};
    }
    if (const auto p = PaperSummaryFor(d.map_name, !e.method.error_free)) {
      if (e.method.Id() == "deterministic" || e.method.Id() == "no-error") {
        x["paper_table_6_22"] = {{"edges", p->edges},
                                 {"distance_ft", p->distance_ft},
                                 {"time_s", p->time_s},
                                 {"accuracy_pct", p->accuracy_pct}};
      }
    }
    j["experiments"].push_back(x);
  }
  return j;
}

void WritePngs(const std::string& dir, const DomainResult& d, const StudyOptions& o) {
  std::filesystem::create_directories(dir);
  for (const ExperimentResult& e : d.experiments) {
    const std::vector<int> edges = EdgeCounts(e, o.runs);
    if (edges.empty()) continue;
    const int hi = std::max(10, *std::max_element(edges.begin(), edges.end()));
    std::string title;
    if (e.method.Id() == "no-error") {
      title = "Unique pose without error (Figure 6.3): " + DomainLabel(d.map_name);
    } else if (e.method.Id() == "deterministic") {
      title = "Multi-sequence with error (Figure 6.5): " + DomainLabel(d.map_name);
    } else {
      title = e.method.Id() + " with error: " + DomainLabel(d.map_name);
    }
    title += fmt::format(" (median trial, seed {})", o.seed);
    const plot::BarChart chart = plot::IntegerHistogramOf(edges, 1, std::min(hi, 120), title,
                                                          "edges sensed before the pose", "runs");
    plot::WriteBarChartPng(chart, dir + "/" + d.map_name + "_" + e.method.Id() + ".png");
  }
}

class ProgressBar {
 public:
  explicit ProgressBar(bool enabled) : enabled_(enabled && isatty(STDERR_FILENO)) {}
  void Draw(const std::string& label, std::uint64_t done, std::uint64_t total) {
    if (!enabled_) return;
    const int width = 40;
    const int fill = total > 0 ? static_cast<int>(width * done / total) : width;
    std::fprintf(stderr, "\r%-24s [%s%s] %3d%%", label.c_str(), std::string(fill, '#').c_str(),
                 std::string(width - fill, ' ').c_str(),
                 total > 0 ? static_cast<int>(100 * done / total) : 100);
    if (done >= total) std::fprintf(stderr, "\n");
    std::fflush(stderr);
  }

 private:
  bool enabled_;
};

}  // namespace

std::optional<PaperLines> PaperLinesFor(const std::string& map_name, const std::string& method) {
  for (const PaperEntry& e : kPaperLines) {
    if (map_name == e.map && method == e.method) return e.lines;
  }
  return std::nullopt;
}

std::optional<PaperSummary> PaperSummaryFor(const std::string& map_name, bool with_error) {
  if (with_error) {
    for (const PaperModeled& m : kPaperModeled) {
      if (map_name == m.map) return m.s;
    }
    return std::nullopt;
  }
  if (const auto* f = map::paper::NoErrorFor(map_name)) {
    return PaperSummary{f->edges, f->distance_ft, f->time_s, 100.0};
  }
  return std::nullopt;
}

std::string DomainLabel(const std::string& map_name) {
  if (const auto* f = map::paper::NoErrorFor(map_name)) return std::string(f->label);
  return map_name;
}

void PrintDomain(std::ostream& out, const DomainResult& d, const StudyOptions& o) {
  fmt::print(out,
             "\n=== {} ({}: {} edges, mean edge {:.2f} in) — {} trials x {} runs, seed {}, "
             "starts on {}, {:.1f} s ===\n",
             DomainLabel(d.map_name), d.map_name, d.map_edges, d.mean_edge_metric_in, o.trials,
             o.runs, o.seed,
             o.start_rings.empty() ? std::string("every ring")
                                   : fmt::format("{}", fmt::join(o.start_rings, ", ")),
             d.seconds);
  for (const ExperimentResult& e : d.experiments) {
    if (e.method.error_free) continue;
    const auto p = PaperLinesFor(d.map_name, e.method.Id());
    const TrialSummary& t = e.median();
    fmt::print(out, "\n{} {} — median trial {} of {}\n",
               p ? fmt::format("Table {}", p->table) : std::string("(no table in the text)"),
               p ? p->caption : e.method.Id().c_str(), e.median_trial + 1, e.trials.size());
    fmt::print(out, "  {:<52} {:>8} {:>8}\n", e.method.Id(), "ours", "paper");
    auto line = [&](const char* what, double ours, std::optional<double> paper) {
      fmt::print(out, "  {:<52} {:>7.2f}% {:>8}\n", what, ours,
                 paper ? fmt::format("{:.2f}%", *paper) : std::string("-"));
    };
    line("of frame sequences contain error", t.pct_with_error,
         p ? std::optional<double>(p->with_error) : std::nullopt);
    line("of erroneous frame sequences recovered pose", t.pct_recovered,
         p ? std::optional<double>(p->recovered) : std::nullopt);
    line("of frame sequences did not converge", t.pct_not_converged,
         p ? std::optional<double>(p->not_converged) : std::nullopt);
    line("correct poses", t.pct_correct, p ? std::optional<double>(p->correct) : std::nullopt);
    line("incorrect poses", t.pct_incorrect,
         p ? std::optional<double>(p->incorrect) : std::nullopt);
  }
  // All methods of this domain side by side, with the spread over trials.
  fmt::print(out, "\n  {:<15} {:>7} {:>7} {:>7} {:>8} {:>8} {:>7} {:>8} {:>7} {:>9}  {}\n",
             "method", "error%", "recov%", "noconv%", "correct%", "incorr%", "edges", "dist ft",
             "time s", "restarts", "correct% over trials (min-max)");
  for (const ExperimentResult& e : d.experiments) {
    const TrialSummary& t = e.median();
    double lo = 100, hi = 0;
    for (const TrialSummary& x : e.trials) {
      lo = std::min(lo, x.pct_correct);
      hi = std::max(hi, x.pct_correct);
    }
    fmt::print(out,
               "  {:<15} {:>7.2f} {:>7.2f} {:>7.2f} {:>8.2f} {:>8.2f} {:>7.2f} {:>8.2f} {:>7.2f} "
               "{:>9.2f}  {:.1f}-{:.1f}\n",
               e.method.Id(), t.pct_with_error, t.pct_recovered, t.pct_not_converged, t.pct_correct,
               t.pct_incorrect, t.mean_edges, t.mean_distance_ft, t.mean_time_s, t.mean_restarts,
               lo, hi);
  }
  // The median trial hides how often a method is wrong: a pose declared at a posterior of
  // 0.995 may be wrong 0.5 % of the time, and one trial's wrong poses are few.
  fmt::print(out, "  every run of every trial:\n");
  for (const ExperimentResult& e : d.experiments) {
    const TrialSummary& a = e.all;
    fmt::print(out,
               "  {:<15} {} runs: {:.2f} % correct, {:.2f} % incorrect ({:.0f}), {:.2f} edges\n",
               e.method.Id(), a.runs, a.pct_correct, a.pct_incorrect,
               a.pct_incorrect * a.runs / 100.0, a.mean_edges);
  }
}

void PrintSummary(std::ostream& out, const std::vector<DomainResult>& results) {
  fmt::print(out, "\nTable 6.22  Comparison of domain performance (median trials): ours (paper)\n");
  fmt::print(out, "  {:<16} {:<14} {:>16} {:>18} {:>18} {:>16}\n", "Domain", "Error type", "Edges",
             "Distance (ft)", "Time (sec)", "Accuracy (%)");
  for (const DomainResult& d : results) {
    auto row = [&](const char* label, const ExperimentResult* e, std::optional<PaperSummary> p) {
      if (e == nullptr) return;
      const TrialSummary& t = e->median();
      fmt::print(
          out, "  {:<16} {:<14} {:>16} {:>18} {:>18} {:>16}\n", DomainLabel(d.map_name), label,
          fmt::format("{:.2f} ({})", t.mean_edges, Paper(p ? p->edges : std::optional<double>())),
          fmt::format("{:.2f} ({})", t.mean_distance_ft,
                      Paper(p ? p->distance_ft : std::optional<double>())),
          fmt::format("{:.2f} ({})", t.mean_time_s, Paper(p ? p->time_s : std::optional<double>())),
          fmt::format("{:.1f} ({})", t.pct_correct,
                      Paper(p ? p->accuracy_pct : std::optional<double>(), 1)));
    };
    row("None", d.Find("no-error"), PaperSummaryFor(d.map_name, false));
    row("Modeled", d.Find("deterministic"), PaperSummaryFor(d.map_name, true));
    row("Modeled, Bayes", d.Find("bayes"), std::nullopt);
  }
  fmt::print(out,
             "\nBayes filter vs deterministic recovery on the same runs (modeled error, median "
             "trials)\n");
  fmt::print(out, "  {:<16} {:>14} {:>14} {:>12} {:>12} {:>14} {:>14}\n", "Domain", "determ. corr%",
             "Bayes corr%", "determ. edg", "Bayes edg", "determ. incorr%", "Bayes incorr%");
  for (const DomainResult& d : results) {
    const ExperimentResult* det = d.Find("deterministic");
    const ExperimentResult* bay = d.Find("bayes");
    if (det == nullptr || bay == nullptr) continue;
    fmt::print(out, "  {:<16} {:>14.2f} {:>14.2f} {:>12.2f} {:>12.2f} {:>14.2f} {:>14.2f}\n",
               DomainLabel(d.map_name), det->median().pct_correct, bay->median().pct_correct,
               det->median().mean_edges, bay->median().mean_edges, det->median().pct_incorrect,
               bay->median().pct_incorrect);
  }
}

namespace {

// (map path, methods) per domain.
using StudyPlan = std::vector<std::pair<std::string, std::vector<MethodSpec>>>;

// The options every domain shares; `current_file` names the file being read, for errors.
StudyOptions LoadBaseOptions(const ToolOptions& opt, const std::string& root,
                             std::string& current_file) {
  StudyOptions base;
  base.trials = opt.trials;
  base.runs = opt.runs;
  base.seed = opt.seed;
  base.threads = opt.threads;
  base.start_rings = opt.start_rings;
  current_file = opt.error_model_path.empty() ? root + "/configs/error_model_paper.yaml"
                                              : opt.error_model_path;
  base.error_model = LoadErrorModel(current_file);
  current_file = opt.config_path.empty() ? root + "/configs/study.yaml" : opt.config_path;
  base.config = LoadStudyConfig(current_file);
  current_file.clear();
  return base;
}

// Chapter 6 whole: the five domains of §6.8 with the methods the text studied on each.
StudyPlan PaperSuitePlan(const std::string& root) {
  StudyPlan plan;
  for (const char* name : kSuiteMaps) {
    std::vector<std::string> ids = {"no-error", "deterministic", "bayes"};
    if (std::string(name) == "engineering_building_3f") {
      // §6.6: the heuristics were studied on the Engineering Building only.
      ids = {"no-error", "none",       "relaxation",    "first-frame", "false-door",
             "missized", "full-suite", "deterministic", "bayes"};
    }
    std::vector<MethodSpec> methods;
    for (const auto& id : ids) methods.push_back(ParseMethod(id));
    plan.push_back({root + "/maps/" + name + ".yaml", methods});
  }
  return plan;
}

// The suite's domains, then the maps given; nothing (with the reason on `err`) for a bad
// suite or no domain at all.
std::optional<StudyPlan> PlanDomains(const ToolOptions& opt, const std::string& root,
                                     std::ostream& err) {
  StudyPlan plan;
  if (opt.suite == "paper") {
    plan = PaperSuitePlan(root);
  } else if (!opt.suite.empty()) {
    err << "stickrep-study: unknown suite '" << opt.suite << "' (known: paper)\n";
    return std::nullopt;
  }
  std::vector<MethodSpec> methods;
  for (const auto& id : opt.methods.empty()
                            ? std::vector<std::string>{"no-error", "deterministic", "bayes"}
                            : opt.methods) {
    methods.push_back(ParseMethod(id));
  }
  for (const auto& m : opt.maps) plan.push_back({m, methods});
  if (plan.empty()) {
    err << "stickrep-study: give a map file or --suite paper\n";
    return std::nullopt;
  }
  return plan;
}

std::vector<map::Map> LoadPlannedMaps(const StudyPlan& plan, std::string& current_file) {
  std::vector<map::Map> maps;
  for (const auto& [path, m] : plan) {
    current_file = path;
    maps.push_back(map::LoadMap(path));
    if (maps.back().EdgeCount() == 0) {
      throw InputError(path, 0, "rings", "the map has no edges: nothing to match against");
    }
  }
  current_file.clear();
  return maps;
}

// The domains studied, in plan order, with the options each was run with.
struct StudyRun {
  std::vector<DomainResult> results;
  std::vector<StudyOptions> used;
  double seconds = 0;
};

// Runs the domains one after the other, printing each as it ends.
StudyRun RunDomains(const ToolOptions& opt, const StudyOptions& base, const StudyPlan& plan,
                    const std::vector<map::Map>& maps, ProgressBar& bar, std::ostream& out) {
  StudyRun run;
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < plan.size(); ++i) {
    StudyOptions o = base;
    o.methods = plan[i].second;
    const std::string label = DomainLabel(maps[i].info().name);
    o.progress = [&bar, label](std::uint64_t done, std::uint64_t total) {
      bar.Draw(label, done, total);
    };
    run.results.push_back(RunStudy(maps[i], o));
    run.used.push_back(o);
    PrintDomain(out, run.results.back(), o);
    if (!opt.png_dir.empty()) WritePngs(opt.png_dir, run.results.back(), o);
  }
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return run;
}

void WriteStudyJson(const ToolOptions& opt, const StudyOptions& base, const StudyRun& run) {
  nlohmann::json j;
  j["seed"] = opt.seed;
  j["trials"] = opt.trials;
  j["runs"] = opt.runs;
  j["seconds"] = run.seconds;
  j["error_model"] = {{"source", base.error_model.source},
                      {"door_correct", base.error_model.door_correct},
                      {"door_missized", base.error_model.door_missized},
                      {"door_missed", base.error_model.door_missed},
                      {"wall_false_door", base.error_model.wall_false_door}};
  for (std::size_t i = 0; i < run.results.size(); ++i) {
    j["domains"].push_back(DomainJson(run.results[i], run.used[i]));
  }
  std::ofstream f(opt.json_path);
  if (!f) throw std::runtime_error("cannot write " + opt.json_path);
  f << j.dump(1) << "\n";
}

}  // namespace

int RunTool(const ToolOptions& opt, std::ostream& out, std::ostream& err) {
  const std::string root = DataDir();
  std::string current_file;
  try {
    if (opt.trials < 1 || opt.runs < 1) {
      err << "stickrep-study: trials and runs must be at least 1 (got " << opt.trials << " x "
          << opt.runs << ")\n";
      return kExitBadInput;
    }
    const StudyOptions base = LoadBaseOptions(opt, root, current_file);
    const std::optional<StudyPlan> plan = PlanDomains(opt, root, err);
    if (!plan) return kExitBadInput;
    const std::vector<map::Map> maps = LoadPlannedMaps(*plan, current_file);

    fmt::print(
        out, "stickrep-study: seed {}, {} trials x {} runs, error model '{}', {} thread(s)\n",
        opt.seed, opt.trials, opt.runs, base.error_model.source,
        opt.threads > 0 ? opt.threads
                        : static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
    ProgressBar bar(opt.progress);
    const StudyRun run = RunDomains(opt, base, *plan, maps, bar, out);
    PrintSummary(out, run.results);
    fmt::print(out, "\nWhole study: {:.1f} s; seed {}.\n", run.seconds, opt.seed);
    if (!opt.json_path.empty()) WriteStudyJson(opt, base, run);
    return 0;
  } catch (const InputError& e) {
    err << FormatInputError(e.file(), e.line(), e.key(), e.reason()) << "\n";
    return kExitBadInput;
  } catch (const std::invalid_argument& e) {
    err << (current_file.empty() ? std::string("stickrep-study") : current_file) << ": " << e.what()
        << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    err << "stickrep-study: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace stickrep::recovery::report
