#pragma once

// Pose integrity over many Where-am-I runs: how long a wrong pose stayed LOCALIZED after a
// kidnap (in sensed edges and feet), the LOSTs said while the pose was right, and whether
// the published confidence means what it says (a reliability table).

#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "whereami/whereami_run.h"

namespace stickrep::whereami {

struct Spread {
  int n = 0;
  double median = 0.0, p95 = 0.0, max = 0.0;
};
Spread SpreadOf(const std::vector<double>& values);

struct IntegritySummary {
  int kidnaps = 0;             // runs kidnapped while LOCALIZED
  // Of the wrong pose's spell after each such kidnap: the edges sensed from the kidnap on,
  // and the feet.
  Spread edges, feet;
  // The edges the localizer took in during the spell: those sensed from the kidnap on and
  // those the robot had sensed before it (WrongSpell::edges_sensed_before).
  Spread edges_taken_in;
  Spread alike;                // edges the map shows alike at the old and the new place
  int within_alike_plus_2 = 0; // spells no longer than the edges alike plus 2
  // The sensed edges each spell lasted past the edges alike (0 where it ended within them):
  // what the localizer took once the map could tell the two places apart.
  Spread past_alike;
  std::vector<std::pair<std::string, int>> ended_by;  // how those spells ended
  int watched_runs = 0;        // runs watched after their first pose
  int false_losts = 0;         // LOST said for a right pose with no kidnap to notice
  int right_poses_given_up = 0;  // a right LOCALIZED pose left without a kidnap
  int runs_with_false_lost = 0;
  int wrong_spells = 0;        // wrong LOCALIZED spells outside a kidnap's
  Spread wrong_spell_edges;
  // The LOCALIZED poses the filter gave up (RunResult::given_up), by what they were: how
  // many, how many of them LOST (the rest RECOVERING), and the least and the median belief
  // the filter had in them then.
  struct GivenUp {
    std::string pose;
    int n = 0;
    int lost = 0;
    double least_belief = 1.0;
    double median_belief = 0.0;
  };
  std::vector<GivenUp> given_up;  // right, kidnap, wrong: those that occurred
};
IntegritySummary SummarizeIntegrity(const std::vector<RunResult>& results);
void PrintIntegrity(const IntegritySummary& s, std::ostream& out);

// Published poses by the confidence they came with: how many, their mean confidence and the
// share that named the true place.
struct ReliabilityBin {
  double lo = 0.0, hi = 1.0;
  int n = 0;
  double mean_confidence = 0.0;
  double correct = 0.0;  // share
};
struct Reliability {
  std::vector<ReliabilityBin> all;        // every pose sample with a candidate
  std::vector<ReliabilityBin> localized;  // those published as LOCALIZED
  // Platt scaling of every sample (localizer/confidence_calibration.h): the maximum-likelihood
  // logit(right) = slope * logit(published) + offset. Run with the calibration off (slope 1,
  // offset 0) the published confidence is the posterior and the fit is the calibration.
  struct Fit {
    double slope = 1.0, offset = 0.0;
    int n = 0;
  } fit;
};
// The maximum-likelihood logistic fit of `correct` on the logit of `confidence` (clipped to
// [1e-6, 1 - 1e-6]); slope 1, offset 0 for fewer than two samples or one outcome only.
Reliability::Fit FitPlatt(const std::vector<ConfidenceSample>& samples);
Reliability ReliabilityOf(const std::vector<RunResult>& results);
void PrintReliability(const Reliability& r, std::ostream& out);

nlohmann::json ToJson(const IntegritySummary& s);
nlohmann::json ToJson(const Reliability& r);

}  // namespace stickrep::whereami
