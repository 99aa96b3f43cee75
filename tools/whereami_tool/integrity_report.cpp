#include "whereami_tool/integrity_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "common/quantile.h"

namespace stickrep::whereami {

namespace {

// Confidence bins, finer toward certainty where the localizer decides.
constexpr double kBinEdges[] = {0.0, 0.5, 0.8, 0.9, 0.95, 0.99, 0.995, 0.999, 1.0 + 1e-12};

std::vector<ReliabilityBin> Bin(const std::vector<ConfidenceSample>& samples) {
  std::vector<ReliabilityBin> bins;
  for (std::size_t i = 0; i + 1 < std::size(kBinEdges); ++i) {
    bins.push_back({kBinEdges[i], std::min(1.0, kBinEdges[i + 1]), 0, 0.0, 0.0});
  }
  for (const ConfidenceSample& c : samples) {
    for (std::size_t i = 0; i + 1 < std::size(kBinEdges); ++i) {
      if (c.confidence >= kBinEdges[i] && c.confidence < kBinEdges[i + 1]) {
        ReliabilityBin& b = bins[i];
        ++b.n;
        b.mean_confidence += c.confidence;
        b.correct += c.correct ? 1.0 : 0.0;
        break;
      }
    }
  }
  for (ReliabilityBin& b : bins) {
    if (b.n == 0) continue;
    b.mean_confidence /= b.n;
    b.correct /= b.n;
  }
  return bins;
}

void PrintBins(const std::vector<ReliabilityBin>& bins, std::ostream& out) {
  out << fmt::format("  {:<16} {:>7} {:>16} {:>14}\n", "confidence", "poses", "mean confidence",
                     "correct");
  for (const ReliabilityBin& b : bins) {
    if (b.n == 0) continue;
    out << fmt::format("  [{:.3f}, {:.3f}{} {:>7} {:>16.4f} {:>14.4f}\n", b.lo, b.hi,
                       b.hi >= 1.0 ? "]" : ")", b.n, b.mean_confidence, b.correct);
  }
}

nlohmann::json ToJson(const Spread& s) {
  return {{"n", s.n}, {"median", s.median}, {"p95", s.p95}, {"max", s.max}};
}

nlohmann::json ToJson(const std::vector<ReliabilityBin>& bins) {
  nlohmann::json j = nlohmann::json::array();
  for (const ReliabilityBin& b : bins) {
    j.push_back({{"lo", b.lo}, {"hi", b.hi}, {"n", b.n}, {"mean_confidence", b.mean_confidence},
                 {"correct", b.correct}});
  }
  return j;
}

}  // namespace

Spread SpreadOf(const std::vector<double>& values) {
  Spread s;
  s.n = static_cast<int>(values.size());
  if (values.empty()) return s;
  s.median = Median(values);
  s.p95 = Quantile(values, 0.95);
  s.max = *std::max_element(values.begin(), values.end());
  return s;
}

IntegritySummary SummarizeIntegrity(const std::vector<RunResult>& results) {
  IntegritySummary s;
  std::vector<double> edges, delivered, feet, wrong_edges, alike, past_alike;
  std::map<std::string, int> ended_by;
  std::map<std::string, std::vector<double>> given_up_beliefs;
  std::map<std::string, int> given_up_lost;
  for (const RunResult& r : results) {
    for (const RunResult::GivenUpPose& g : r.given_up) {
      given_up_beliefs[g.pose].push_back(g.belief);
      given_up_lost[g.pose] += g.lost;
    }
    if (r.first) ++s.watched_runs;
    s.false_losts += r.false_losts;
    s.right_poses_given_up += r.right_poses_given_up;
    s.runs_with_false_lost += r.false_losts > 0;
    for (const WrongSpell& w : r.wrong_localized) {
      ++s.wrong_spells;
      wrong_edges.push_back(static_cast<double>(w.edges));
    }
    if (!r.after_kidnap || r.after_kidnap->ended_by == "not localized at the kidnap") continue;
    ++s.kidnaps;
    const long after = r.after_kidnap->edges - r.after_kidnap->edges_sensed_before;
    edges.push_back(static_cast<double>(after));
    delivered.push_back(static_cast<double>(r.after_kidnap->edges));
    alike.push_back(r.kidnap_edges_alike);
    s.within_alike_plus_2 += after <= r.kidnap_edges_alike + 2;
    past_alike.push_back(static_cast<double>(std::max(0L, after - r.kidnap_edges_alike)));
    feet.push_back(r.after_kidnap->distance_ft);
    ++ended_by[r.after_kidnap->ended_by];
  }
  s.edges = SpreadOf(edges);
  s.edges_taken_in = SpreadOf(delivered);
  s.feet = SpreadOf(feet);
  s.wrong_spell_edges = SpreadOf(wrong_edges);
  s.alike = SpreadOf(alike);
  s.past_alike = SpreadOf(past_alike);
  s.ended_by.assign(ended_by.begin(), ended_by.end());
  for (const char* pose : {"right", "kidnap", "wrong"}) {
    const auto it = given_up_beliefs.find(pose);
    if (it == given_up_beliefs.end()) continue;
    const std::vector<double>& b = it->second;
    s.given_up.push_back({pose, static_cast<int>(b.size()), given_up_lost[pose],
                          *std::min_element(b.begin(), b.end()), Median(b)});
  }
  return s;
}

void PrintIntegrity(const IntegritySummary& s, std::ostream& out) {
  out << "\nintegrity (every published pose judged against the truth, from the first pose on):\n";
  if (s.kidnaps > 0) {
    std::string ends;
    for (const auto& [how, n] : s.ended_by) ends += fmt::format("{}{} {}", ends.empty() ? "" : ", ", n, how);
    out << fmt::format(
        "  after {} kidnaps the wrong pose stayed LOCALIZED for sensed edges median {:.0f}, "
        "95th percentile {:.0f}, max {:.0f}; feet median {:.1f}, 95th percentile {:.1f}, max "
        "{:.1f}; ended by: {}\n",
        s.kidnaps, s.edges.median, s.edges.p95, s.edges.max, s.feet.median, s.feet.p95,
        s.feet.max, ends);
    out << fmt::format(
        "  (edges sensed from the kidnap on; the localizer took in median {:.0f}, 95th "
        "percentile {:.0f}, max {:.0f} meanwhile, with those sensed before the kidnap and "
        "decided after it)\n",
        s.edges_taken_in.median, s.edges_taken_in.p95, s.edges_taken_in.max);
    out << fmt::format(
        "  the map shows the old place and the new alike for edges median {:.0f}, 95th "
        "percentile {:.0f}, max {:.0f}; {} of {} spells ended within 2 edges of that\n",
        s.alike.median, s.alike.p95, s.alike.max, s.within_alike_plus_2, s.kidnaps);
    out << fmt::format(
        "  sensed edges the wrong pose stayed LOCALIZED past those alike: median {:.0f}, 95th "
        "percentile {:.0f}, max {:.0f}\n",
        s.past_alike.median, s.past_alike.p95, s.past_alike.max);
  }
  out << fmt::format(
      "  {} runs watched: {} LOST said while the pose was right ({} runs); {} right poses given "
      "up with no kidnap to notice (to RECOVERING or LOST); {} other spells of a wrong LOCALIZED "
      "pose{}\n",
      s.watched_runs, s.false_losts, s.runs_with_false_lost, s.right_poses_given_up, s.wrong_spells,
      s.wrong_spells > 0 ? fmt::format(" (sensed edges median {:.0f}, max {:.0f})",
                                       s.wrong_spell_edges.median, s.wrong_spell_edges.max)
                         : std::string());
  // Sorted by what each pose was when given up: a right pose given up between a kidnap and
  // the next pose (kept across a jump to a place the map shows alike) is counted here too.
  for (const IntegritySummary::GivenUp& g : s.given_up) {
    out << fmt::format(
        "  {} {} poses given up{}: {} LOST, {} RECOVERING; the filter's belief in them then: "
        "least {:.2g}, median {:.2g}\n",
        g.n, g.pose, g.pose == "right" ? " (all, after a kidnap too)" : "", g.lost, g.n - g.lost,
        g.least_belief, g.median_belief);
  }
}

Reliability::Fit FitPlatt(const std::vector<ConfidenceSample>& samples) {
  Reliability::Fit fit;
  fit.n = static_cast<int>(samples.size());
  std::vector<double> x;
  int right = 0;
  for (const ConfidenceSample& c : samples) {
    const double p = std::clamp(c.confidence, 1e-6, 1.0 - 1e-6);
    x.push_back(std::log(p / (1.0 - p)));
    right += c.correct ? 1 : 0;
  }
  if (fit.n < 2 || right == 0 || right == fit.n) return fit;
  const auto log_likelihood = [&](double a, double b) {
    double ll = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      // log sigmoid(z) for a right sample, log sigmoid(-z) for a wrong one, without overflow.
      const double z = (samples[i].correct ? 1.0 : -1.0) * (a * x[i] + b);
      ll -= z > 0.0 ? std::log1p(std::exp(-z)) : -z + std::log1p(std::exp(z));
    }
    return ll;
  };
  // Newton's method on the log-likelihood of the two parameters, from the identity. A full
  // step overshoots when most samples sit at a logit of 14 (posteriors of 1, clamped) and
  // the identity is far from the fit; each step is halved until the likelihood rises.
  double a = 1.0, b = 0.0;
  double ll = log_likelihood(a, b);
  for (int iteration = 0; iteration < 100; ++iteration) {
    double ga = 0, gb = 0, haa = 0, hab = 0, hbb = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double q = 1.0 / (1.0 + std::exp(-(a * x[i] + b)));
      const double r = (samples[i].correct ? 1.0 : 0.0) - q, w = q * (1.0 - q);
      ga += r * x[i];
      gb += r;
      haa += w * x[i] * x[i];
      hab += w * x[i];
      hbb += w;
    }
    const double det = haa * hbb - hab * hab;
    if (!(det > 0.0)) break;
    const double da = (hbb * ga - hab * gb) / det, db = (haa * gb - hab * ga) / det;
    double t = 1.0, next = log_likelihood(a + da, b + db);
    for (int halving = 0; halving < 40 && !(next >= ll); ++halving) {
      t *= 0.5;
      next = log_likelihood(a + t * da, b + t * db);
    }
    if (!(next >= ll)) break;
    a += t * da;
    b += t * db;
    ll = next;
    if (std::abs(t * da) < 1e-9 && std::abs(t * db) < 1e-9) break;
  }
  fit.slope = a;
  fit.offset = b;
  return fit;
}

Reliability ReliabilityOf(const std::vector<RunResult>& results) {
  std::vector<ConfidenceSample> all, localized;
  for (const RunResult& r : results) {
    for (const ConfidenceSample& c : r.confidences) {
      all.push_back(c);
      if (c.localized) localized.push_back(c);
    }
  }
  return {Bin(all), Bin(localized), FitPlatt(all)};
}

void PrintReliability(const Reliability& r, std::ostream& out) {
  out << "\nreliability: poses published with a confidence, and the share that named the true "
         "place (a sample at each sensed edge and each change of status)\n";
  out << " every pose with a candidate:\n";
  PrintBins(r.all, out);
  out << " poses published as LOCALIZED:\n";
  PrintBins(r.localized, out);
  out << fmt::format(" Platt fit over the {} samples: logit(right) = {:.3f} logit(confidence) "
                     "{:+.3f}\n",
                     r.fit.n, r.fit.slope, r.fit.offset);
}

nlohmann::json ToJson(const IntegritySummary& s) {
  nlohmann::json given_up = nlohmann::json::array();
  for (const IntegritySummary::GivenUp& g : s.given_up) {
    given_up.push_back({{"pose", g.pose}, {"n", g.n}, {"lost", g.lost},
                        {"least_belief", g.least_belief}, {"median_belief", g.median_belief}});
  }
  nlohmann::json ended = nlohmann::json::object();
  for (const auto& [how, n] : s.ended_by) ended[how] = n;
  return {{"kidnaps", s.kidnaps},
          {"wrong_pose_edges", ToJson(s.edges)},
          {"wrong_pose_edges_taken_in", ToJson(s.edges_taken_in)},
          {"wrong_pose_feet", ToJson(s.feet)},
          {"edges_alike", ToJson(s.alike)},
          {"within_alike_plus_2", s.within_alike_plus_2},
          {"edges_past_alike", ToJson(s.past_alike)},
          {"ended_by", ended},
          {"watched_runs", s.watched_runs},
          {"false_losts", s.false_losts},
          {"right_poses_given_up", s.right_poses_given_up},
          {"runs_with_false_lost", s.runs_with_false_lost},
          {"wrong_spells", s.wrong_spells},
          {"wrong_spell_edges", ToJson(s.wrong_spell_edges)},
          {"given_up", given_up}};
}

nlohmann::json ToJson(const Reliability& r) {
  return {{"all", ToJson(r.all)},
          {"localized", ToJson(r.localized)},
          {"fit", {{"slope", r.fit.slope}, {"offset", r.fit.offset}, {"n", r.fit.n}}}};
}

}  // namespace stickrep::whereami
