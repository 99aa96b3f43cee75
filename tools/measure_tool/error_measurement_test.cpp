// The measurement of the landmark pipeline: seeds, thread independence, the Table 6.10
// tally and the error-model file.
#include "measure_tool/error_measurement.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "sensing/robot_config.h"
#include "stickrep/map_io.h"

namespace stickrep::measure {
namespace {

using ::testing::HasSubstr;

map::Map ShippedMap(const std::string& name) {
  return map::LoadMap(std::string(STICKREP_SOURCE_DIR) + "/maps/" + name + ".yaml");
}

FrameResult Result(FrameResult::Outcome outcome, int true_class = -1, int sensed_class = -1) {
  FrameResult r;
  r.outcome = outcome;
  r.truth = (outcome == FrameResult::Outcome::kTrueNegative ||
             outcome == FrameResult::Outcome::kFalsePositive)
                ? FrameResult::Truth::kNegative
                : FrameResult::Truth::kPositive;
  r.true_class = true_class;
  r.sensed_class = sensed_class;
  return r;
}

TEST(TallyTest, RatesFollowTable610) {
  // 8 positives: 5 right, 2 mis-sized, 1 missed; 4 negatives: 3 right, 1 false door.
  Tally t;
  for (int i = 0; i < 5; ++i) t.Add(Result(FrameResult::Outcome::kTruePositive, 2, 2));
  for (int i = 0; i < 2; ++i) t.Add(Result(FrameResult::Outcome::kMissizedPositive, 2, 3));
  t.Add(Result(FrameResult::Outcome::kFalseNegative, 2));
  for (int i = 0; i < 3; ++i) t.Add(Result(FrameResult::Outcome::kTrueNegative));
  t.Add(Result(FrameResult::Outcome::kFalsePositive, -1, 0));
  t.Add(Result(FrameResult::Outcome::kDropped));
  EXPECT_EQ(t.frames(), 12);
  EXPECT_EQ(t.dropped, 1);
  EXPECT_DOUBLE_EQ(t.correct_pct(), 100.0 * 8 / 12);
  EXPECT_DOUBLE_EQ(t.tp_pct(), 62.5);
  EXPECT_DOUBLE_EQ(t.missized_pct(), 25.0);
  EXPECT_DOUBLE_EQ(t.fn_pct(), 12.5);
  EXPECT_DOUBLE_EQ(t.tn_pct(), 75.0);
  EXPECT_DOUBLE_EQ(t.fp_pct(), 25.0);
  EXPECT_DOUBLE_EQ(t.correct_pct() + t.misclassified_pct(), 100.0);
}

TEST(ErrorModelYamlTest, WritesTheSchemaTheSimulationReads) {
  Measurement m;
  m.config.seed = 42;
  for (int i = 0; i < 5; ++i) m.all.Add(Result(FrameResult::Outcome::kTruePositive, 2, 2));
  for (int i = 0; i < 2; ++i) m.all.Add(Result(FrameResult::Outcome::kMissizedPositive, 2, 3));
  m.all.Add(Result(FrameResult::Outcome::kFalseNegative, 2));
  for (int i = 0; i < 3; ++i) m.all.Add(Result(FrameResult::Outcome::kTrueNegative));
  m.all.Add(Result(FrameResult::Outcome::kFalsePositive, -1, 0));
  m.missized_to[2][3] = 2;
  m.false_door_classes[0] = 1;
  const std::string yaml = FormatErrorModelYaml(m);
  EXPECT_THAT(yaml, HasSubstr("error_model:\n"));
  EXPECT_THAT(yaml, HasSubstr("  source: \"measured by stickrep-measure, seed 42, 12 frames\"\n"));
  EXPECT_THAT(yaml, HasSubstr("  door_correct: 0.625000\n"));
  EXPECT_THAT(yaml, HasSubstr("  door_missized: 0.250000\n"));
  EXPECT_THAT(yaml, HasSubstr("  door_missed: 0.125000\n"));
  EXPECT_THAT(yaml, HasSubstr("  wall_false_door: 0.250000\n"));
  EXPECT_THAT(yaml, HasSubstr("  missized_to: {\"36\": {\"40\": 1.000000}}\n"));
  EXPECT_THAT(yaml, HasSubstr("  false_door_classes: {\"30\": 1.000000}\n"));
}

TEST(MeasurePipelineTest, ResultsDoNotDependOnThreadCount) {
  const std::vector<map::Map> maps{ShippedMap("wells_hall_7f"), ShippedMap("storefront")};
  MeasureConfig config;
  config.seed = 5;
  config.frames = 24;
  config.threads = 1;
  const Measurement one = MeasurePipeline(maps, sensing::RobotConfig{}, config);
  config.threads = 2;
  const Measurement two = MeasurePipeline(maps, sensing::RobotConfig{}, config);
  ASSERT_EQ(one.frames.size(), two.frames.size());
  for (std::size_t i = 0; i < one.frames.size(); ++i) {
    EXPECT_EQ(one.frames[i].outcome, two.frames[i].outcome) << i;
    EXPECT_EQ(one.frames[i].sensed_class, two.frames[i].sensed_class) << i;
    EXPECT_EQ(one.frames[i].sensed_width_in, two.frames[i].sensed_width_in) << i;
  }
  EXPECT_EQ(FormatErrorModelYaml(one), FormatErrorModelYaml(two));
  EXPECT_EQ(one.all.frames() + one.all.dropped, 24);
  EXPECT_EQ(one.per_map[0].frames() + one.per_map[0].dropped, 12);  // frame i on map i mod 2
}

TEST(MeasurePipelineTest, InsideTheEnvelopeMostFramesAreRight) {
  const std::vector<map::Map> maps{ShippedMap("wells_hall_7f")};
  MeasureConfig config;
  config.seed = 11;
  config.frames = 60;
  config.envelope_share = 1.0;
  config.max_roll_deg = 0.0;
  config.open_door_fraction = 0.0;
  const Measurement m = MeasurePipeline(maps, sensing::RobotConfig{}, config);
  EXPECT_GT(m.all.positives(), 5);
  EXPECT_GT(m.all.negatives(), 5);
  EXPECT_GT(m.all.correct_pct(), 60.0) << FormatReport(m);
}

TEST(MeasurePipelineTest, RejectsBadConfig) {
  const std::vector<map::Map> maps{ShippedMap("wells_hall_7f")};
  MeasureConfig config;
  config.frames = 0;
  EXPECT_THROW(MeasurePipeline(maps, sensing::RobotConfig{}, config), std::invalid_argument);
  config = {};
  config.envelope_share = 2.0;
  EXPECT_THROW(MeasurePipeline(maps, sensing::RobotConfig{}, config), std::invalid_argument);
  EXPECT_THROW(MeasurePipeline({}, sensing::RobotConfig{}, MeasureConfig{}), std::invalid_argument);
}

}  // namespace
}  // namespace stickrep::measure
