// The integrity and reliability figures of a stickrep-whereami batch, added up from runs.
#include "whereami_tool/integrity_report.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace stickrep::whereami {
namespace {

RunResult KidnapRun(long edges, double feet, int alike, const std::string& ended_by) {
  RunResult r;
  r.first = virtual_robot::PoseCheck{};
  r.kidnapped = true;
  r.after_kidnap = WrongSpell{edges, feet, ended_by};
  r.kidnap_edges_alike = alike;
  return r;
}

TEST(IntegrityReportTest, KidnapSpellsAreSpreadAndCountedAgainstTheEdgesAlike) {
  std::vector<RunResult> runs = {KidnapRun(1, 10.0, 0, "RECOVERING"),
                                 KidnapRun(2, 20.0, 1, "RECOVERING"),
                                 KidnapRun(6, 80.0, 1, "LOST")};
  // A run whose pose had been given up before the kidnap has no spell to count.
  runs.push_back(KidnapRun(0, 0.0, 0, "not localized at the kidnap"));
  const IntegritySummary s = SummarizeIntegrity(runs);
  EXPECT_EQ(s.kidnaps, 3);
  EXPECT_EQ(s.watched_runs, 4);
  EXPECT_DOUBLE_EQ(s.edges.median, 2.0);
  EXPECT_DOUBLE_EQ(s.edges.max, 6.0);
  EXPECT_DOUBLE_EQ(s.feet.max, 80.0);
  EXPECT_EQ(s.within_alike_plus_2, 2);  // 6 edges against 1 alike is beyond
  // Past the edges alike: 1, 1 and 5.
  EXPECT_DOUBLE_EQ(s.past_alike.median, 1.0);
  EXPECT_DOUBLE_EQ(s.past_alike.max, 5.0);
  EXPECT_EQ(s.past_alike.n, 3);
  ASSERT_EQ(s.ended_by.size(), 2u);
  EXPECT_EQ(s.ended_by[0], (std::pair<std::string, int>{"LOST", 1}));
  EXPECT_EQ(s.ended_by[1], (std::pair<std::string, int>{"RECOVERING", 2}));
}

// A door is taken in once the camera is past it, the wall before it with it: edges sensed
// at the old place before the kidnap may reach the localizer after it. They are no evidence
// of the kidnap, so the spell is counted from the edge the robot was kidnapped in.
TEST(IntegrityReportTest, EdgesSensedBeforeTheKidnapAreNotCountedInItsSpell) {
  std::vector<RunResult> runs = {KidnapRun(4, 10.0, 1, "RECOVERING"),
                                 KidnapRun(3, 12.0, 1, "RECOVERING")};
  runs[0].after_kidnap->edges_sensed_before = 2;
  const IntegritySummary s = SummarizeIntegrity(runs);
  EXPECT_DOUBLE_EQ(s.edges.max, 3.0);  // 4 - 2 and 3 - 0
  EXPECT_DOUBLE_EQ(s.edges.median, 2.5);
  EXPECT_DOUBLE_EQ(s.edges_taken_in.max, 4.0);
  EXPECT_DOUBLE_EQ(s.past_alike.max, 2.0);
  EXPECT_DOUBLE_EQ(s.past_alike.median, 1.5);
  EXPECT_EQ(s.within_alike_plus_2, 2);
  std::ostringstream out;
  PrintIntegrity(s, out);
  EXPECT_NE(out.str().find("the localizer took in median 4, 95th percentile 4, max 4 meanwhile"),
            std::string::npos)
      << out.str();
  EXPECT_EQ(ToJson(s)["wrong_pose_edges_taken_in"]["max"], 4.0);
}

TEST(IntegrityReportTest, PosesGivenUpAreGroupedByWhatTheyWereWithTheBeliefThen) {
  RunResult a;
  a.first = virtual_robot::PoseCheck{};
  a.given_up = {{"right", 0.5, false, std::nullopt},
                {"kidnap", 2e-5, true, 1e-6},
                {"right", 0.0027, false, 0.004}};
  RunResult b;
  b.first = virtual_robot::PoseCheck{};
  b.given_up = {{"kidnap", 0.3, false, std::nullopt}, {"right", 0.8, false, std::nullopt}};
  b.false_losts = 1;
  const IntegritySummary s = SummarizeIntegrity({a, b});
  ASSERT_EQ(s.given_up.size(), 2u);  // no wrong pose given up: no row
  EXPECT_EQ(s.given_up[0].pose, "right");
  EXPECT_EQ(s.given_up[0].n, 3);
  EXPECT_EQ(s.given_up[0].lost, 0);
  EXPECT_DOUBLE_EQ(s.given_up[0].least_belief, 0.0027);
  EXPECT_DOUBLE_EQ(s.given_up[0].median_belief, 0.5);
  EXPECT_EQ(s.given_up[1].pose, "kidnap");
  EXPECT_EQ(s.given_up[1].n, 2);
  EXPECT_EQ(s.given_up[1].lost, 1);
  EXPECT_DOUBLE_EQ(s.given_up[1].least_belief, 2e-5);
  EXPECT_EQ(s.false_losts, 1);
  EXPECT_EQ(s.runs_with_false_lost, 1);
  std::ostringstream out;
  PrintIntegrity(s, out);
  EXPECT_NE(out.str().find("3 right poses given up (all, after a kidnap too): 0 LOST, 3 "
                           "RECOVERING; the filter's belief "
                           "in them then: least 0.0027, median 0.5"),
            std::string::npos)
      << out.str();
  EXPECT_EQ(ToJson(s)["given_up"][1]["lost"], 1);
}

TEST(IntegrityReportTest, ReliabilityBinsCountTheShareOfPosesThatWereRight) {
  RunResult r;
  r.confidences = {{0.97, true, true}, {0.96, true, false}, {0.3, false, false},
                   {0.999, true, true}};
  const Reliability rel = ReliabilityOf({r});
  int all = 0;
  for (const ReliabilityBin& b : rel.all) all += b.n;
  EXPECT_EQ(all, 4);
  const auto bin_of = [](const std::vector<ReliabilityBin>& bins, double c) {
    for (const ReliabilityBin& b : bins) {
      if (c >= b.lo && c < b.hi) return b;
    }
    return bins.back();
  };
  const ReliabilityBin b = bin_of(rel.localized, 0.96);
  EXPECT_EQ(b.n, 2);
  EXPECT_DOUBLE_EQ(b.correct, 0.5);
  EXPECT_DOUBLE_EQ(b.mean_confidence, (0.97 + 0.96) / 2.0);
  EXPECT_EQ(bin_of(rel.localized, 0.3).n, 0);  // not published as LOCALIZED
}

TEST(IntegrityReportTest, PlattFitRecoversTheCurveTheSamplesWereDrawnFrom) {
  // Samples right with probability sigmoid(0.7 logit(p) - 1.0), on a grid of posteriors:
  // the fit finds the two parameters back.
  std::vector<ConfidenceSample> samples;
  std::mt19937_64 rng(20261126);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 20000; ++i) {
    const double p = 0.02 + 0.9799 * u(rng);
    const double z = 0.7 * std::log(p / (1.0 - p)) - 1.0;
    samples.push_back({p, false, u(rng) < 1.0 / (1.0 + std::exp(-z))});
  }
  const Reliability::Fit fit = FitPlatt(samples);
  EXPECT_EQ(fit.n, 20000);
  EXPECT_NEAR(fit.slope, 0.7, 0.05);
  EXPECT_NEAR(fit.offset, -1.0, 0.08);
  // One outcome only: nothing to fit.
  const Reliability::Fit none = FitPlatt({{0.9, true, true}, {0.8, true, true}});
  EXPECT_DOUBLE_EQ(none.slope, 1.0);
  EXPECT_DOUBLE_EQ(none.offset, 0.0);
}

TEST(IntegrityReportTest, PlattFitConvergesWhenMostSamplesSitAtTheTop) {
  // A filter sure of most places: a third of the samples at a posterior of 1 (clamped to
  // 1 - 1e-6), right 96.7 % of the time, the rest spread below and right far less often than
  // said. Undamped Newton steps from the identity overshoot here and diverge; the fit must
  // still end at the maximum of the likelihood.
  const struct {
    double confidence;
    int n, right;
  } bins[] = {{0.2184, 4273, 421},  {0.6453, 2342, 719}, {0.8534, 878, 393},
              {0.9257, 588, 296},   {0.9747, 1123, 732}, {0.9926, 351, 284},
              {0.9974, 656, 529},   {1.0, 2358, 2280}};
  std::vector<ConfidenceSample> samples;
  for (const auto& b : bins) {
    for (int i = 0; i < b.n; ++i) samples.push_back({b.confidence, false, i < b.right});
  }
  const Reliability::Fit fit = FitPlatt(samples);
  ASSERT_TRUE(std::isfinite(fit.slope) && std::isfinite(fit.offset));
  EXPECT_GT(fit.slope, 0.1);
  EXPECT_LT(fit.slope, 1.0);
  // At the maximum the gradient of the log-likelihood vanishes: the fitted confidences sum
  // to the number right, and their logit-weighted sums agree.
  double gb = 0.0, ga = 0.0;
  for (const ConfidenceSample& c : samples) {
    const double p = std::clamp(c.confidence, 1e-6, 1.0 - 1e-6);
    const double x = std::log(p / (1.0 - p));
    const double q = 1.0 / (1.0 + std::exp(-(fit.slope * x + fit.offset)));
    const double r = (c.correct ? 1.0 : 0.0) - q;
    gb += r;
    ga += r * x;
  }
  EXPECT_NEAR(gb, 0.0, 1e-3);
  EXPECT_NEAR(ga, 0.0, 1e-2);
}

}  // namespace
}  // namespace stickrep::whereami
