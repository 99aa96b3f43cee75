#include "study_tool/study.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "recovery/test_support.h"
#include "stickrep/map_io.h"

namespace stickrep::recovery {
namespace {

std::vector<MethodSpec> Methods(std::initializer_list<const char*> ids) {
  std::vector<MethodSpec> out;
  for (const char* id : ids) {
    MethodSpec m;
    if (std::string(id) == "bayes") {
      m.kind = MethodSpec::Kind::kBayes;
    } else {
      m.strategy = *ParseStrategy(id);
    }
    out.push_back(m);
  }
  return out;
}

class StudyTest : public ::testing::Test {
 protected:
  map::Map map_ = map::LoadMap(std::string(STICKREP_SOURCE_DIR) + "/maps/storefront.yaml");
  StudyOptions Options() {
    StudyOptions o;
    o.trials = 3;
    o.runs = 60;
    o.seed = 11;
    o.config.noise.class_region_in = DefaultClassRegions();
    o.methods = Methods({"deterministic", "full-suite", "bayes"});
    return o;
  }
};

TEST_F(StudyTest, SameSeedSameNumbersWhateverTheThreads) {
  StudyOptions one = Options();
  one.threads = 1;
  StudyOptions two = Options();
  two.threads = 2;
  const DomainResult a = RunStudy(map_, one);
  const DomainResult b = RunStudy(map_, two);
  ASSERT_EQ(a.experiments.size(), b.experiments.size());
  for (std::size_t m = 0; m < a.experiments.size(); ++m) {
    const auto& ra = a.experiments[m].runs;
    const auto& rb = b.experiments[m].runs;
    ASSERT_EQ(ra.size(), rb.size());
    for (std::size_t i = 0; i < ra.size(); ++i) {
      EXPECT_EQ(ra[i].outcome, rb[i].outcome);
      EXPECT_EQ(ra[i].edges, rb[i].edges);
      EXPECT_EQ(ra[i].travel_in, rb[i].travel_in);
      EXPECT_EQ(ra[i].had_error, rb[i].had_error);
    }
    EXPECT_EQ(a.experiments[m].median().pct_correct, b.experiments[m].median().pct_correct);
  }
}

TEST_F(StudyTest, DifferentSeedsGiveDifferentRuns) {
  StudyOptions o = Options();
  const DomainResult a = RunStudy(map_, o);
  o.seed = 12;
  const DomainResult b = RunStudy(map_, o);
  int differ = 0;
  for (std::size_t i = 0; i < a.experiments[0].runs.size(); ++i) {
    differ += a.experiments[0].runs[i].edges != b.experiments[0].runs[i].edges;
  }
  EXPECT_GT(differ, 0);
}

TEST_F(StudyTest, WithoutErrorEveryRunEndsWithTheCorrectPose) {
  StudyOptions o = Options();
  o.error_model = ErrorModel::None();
  o.config.noise = SensingNoise::None();
  o.config.noise.class_region_in = DefaultClassRegions();
  o.methods = Methods({"none", "deterministic", "full-suite", "bayes"});
  MethodSpec no_error;
  no_error.error_free = true;
  o.methods.push_back(no_error);
  const DomainResult r = RunStudy(map_, o);
  for (const ExperimentResult& e : r.experiments) {
    for (const TrialSummary& t : e.trials) {
      EXPECT_DOUBLE_EQ(t.pct_correct, 100.0) << e.method.Id();
      EXPECT_DOUBLE_EQ(t.pct_with_error, 0.0) << e.method.Id();
    }
  }
}

TEST_F(StudyTest, ModeledErrorShowsInTheFigures) {
  const DomainResult r = RunStudy(map_, Options());
  const ExperimentResult* det = r.Find("deterministic");
  ASSERT_NE(det, nullptr);
  EXPECT_GT(det->median().pct_with_error, 20.0);
  EXPECT_DOUBLE_EQ(det->median().pct_not_converged, 0.0);
  EXPECT_NEAR(det->median().pct_correct + det->median().pct_incorrect, 100.0, 1e-9);
  EXPECT_GT(det->median().mean_time_s, 0.0);
}

TEST_F(StudyTest, EveryRunOfEveryTrialIsSummedUp) {
  const DomainResult r = RunStudy(map_, Options());
  const ExperimentResult* det = r.Find("deterministic");
  ASSERT_NE(det, nullptr);
  // Trials of equal runs: the whole is their mean, the wrong poses their sum.
  EXPECT_EQ(det->all.runs, 180);
  double incorrect = 0.0, with_error = 0.0;
  for (const TrialSummary& t : det->trials) {
    incorrect += t.pct_incorrect * t.runs / 100.0;
    with_error += t.pct_with_error / 3.0;
  }
  EXPECT_NEAR(det->all.pct_incorrect * det->all.runs / 100.0, incorrect, 1e-9);
  EXPECT_NEAR(det->all.pct_with_error, with_error, 1e-9);
  EXPECT_GT(incorrect, 0.0);
}

TEST_F(StudyTest, ZeroTrialsOrRunsAreRejected) {
  StudyOptions o = Options();
  o.trials = 0;
  EXPECT_THROW(RunStudy(map_, o), std::invalid_argument);
  o = Options();
  o.runs = 0;
  EXPECT_THROW(RunStudy(map_, o), std::invalid_argument);
}

TEST_F(StudyTest, ErrorRateOutsideZeroOneIsRejected) {
  StudyOptions o = Options();
  o.error_model.wall_false_door = 1.5;
  EXPECT_THROW(RunStudy(map_, o), std::invalid_argument);
}

TEST_F(StudyTest, EmptyMapIsRejected) {
  EXPECT_THROW(RunStudy(map::Map(), Options()), std::invalid_argument);
}

TEST_F(StudyTest, AStartRingTheMapDoesNotHaveIsRejected) {
  StudyOptions o = Options();
  o.start_rings = {"no_such_ring"};
  try {
    RunStudy(map_, o);
    FAIL() << "a start ring the map does not have was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_ring"), std::string::npos) << e.what();
  }
}

TEST_F(StudyTest, StartsOnOneRingChangeTheRunsButKeepThemCorrectWithoutError) {
  const map::Map eb =
      map::LoadMap(std::string(STICKREP_SOURCE_DIR) + "/maps/engineering_building_3f.yaml");
  StudyOptions all = Options();
  all.runs = 300;
  all.methods = Methods({"deterministic"});
  all.methods[0].error_free = true;
  StudyOptions one = all;
  one.start_rings = {eb.ring(0).id};
  const DomainResult a = RunStudy(eb, all);
  const DomainResult b = RunStudy(eb, one);
  EXPECT_EQ(b.experiments[0].median().pct_correct, 100.0);
  // The first ring is a corridor of rows of like offices: from it a unique pose takes more
  // edges than from a start anywhere on the floor.
  double edges_all = 0, edges_one = 0;
  for (const TrialSummary& t : a.experiments[0].trials) edges_all += t.mean_edges;
  for (const TrialSummary& t : b.experiments[0].trials) edges_one += t.mean_edges;
  EXPECT_GT(edges_one, edges_all);
}

TEST(StudySummary, CountsTheLinesOfTheTables) {
  std::vector<RunResult> runs(4);
  runs[0] = {Outcome::kCorrect, false, 5, 0, 100};
  runs[1] = {Outcome::kCorrect, true, 7, 1, 200};
  runs[2] = {Outcome::kIncorrect, true, 3, 0, 60};
  runs[3] = {Outcome::kNotConverged, true, 9, 0, 300};
  const TrialSummary t = Summarise(runs.data(), 4, 2.6);
  EXPECT_DOUBLE_EQ(t.pct_with_error, 75.0);
  EXPECT_NEAR(t.pct_recovered, 100.0 / 3.0, 1e-9);
  EXPECT_DOUBLE_EQ(t.pct_not_converged, 25.0);
  EXPECT_DOUBLE_EQ(t.pct_correct, 50.0);
  EXPECT_DOUBLE_EQ(t.pct_incorrect, 25.0);
  EXPECT_DOUBLE_EQ(t.mean_edges, 5.0);
  EXPECT_DOUBLE_EQ(t.mean_distance_ft, 360.0 / 3.0 / 12.0);
}

}  // namespace
}  // namespace stickrep::recovery
