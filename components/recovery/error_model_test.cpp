#include "recovery/error_model.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "common/input_error.h"
#include "recovery/test_support.h"

namespace stickrep::recovery {
namespace {

using map::DoorClass;

std::string Model(const std::string& extra, const std::string& missed = "0.0612") {
  return "error_model:\n"
         "  source: \"test\"\n"
         "  door_correct: 0.8367\n"
         "  door_missized: 0.1020\n"
         "  door_missed: " +
         missed +
         "\n"
         "  wall_false_door: 0.1591\n" +
         extra;
}

TEST(ErrorModelFile, PaperFileHasTheRatesOfTable610) {
  const ErrorModel m =
      LoadErrorModel(std::string(STICKREP_SOURCE_DIR) + "/configs/error_model_paper.yaml");
  EXPECT_DOUBLE_EQ(m.door_correct, 0.8367);
  EXPECT_DOUBLE_EQ(m.door_missized, 0.1020);
  EXPECT_DOUBLE_EQ(m.door_missed, 0.0612);
  EXPECT_DOUBLE_EQ(m.wall_false_door, 0.1591);
  EXPECT_TRUE(m.missized_to.empty());
  EXPECT_TRUE(m.false_door_classes.empty());
}

// Every model file under configs/ loads and validates: a localizer may be pointed at any.
TEST(ErrorModelFile, EveryShippedModelLoads) {
  int files = 0;
  const std::filesystem::path configs = std::string(STICKREP_SOURCE_DIR) + "/configs";
  for (const auto& entry : std::filesystem::directory_iterator(configs)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("error_model_", 0) != 0 || entry.path().extension() != ".yaml") continue;
    ++files;
    SCOPED_TRACE(name);
    const ErrorModel m = LoadErrorModel(entry.path().string());
    EXPECT_NEAR(m.door_correct + m.door_missized + m.door_missed, 1.0, 1e-3);  // Table 6.10: 0.9999
  }
  EXPECT_GE(files, 6);
}

TEST(ErrorModelFile, ReadsOptionalDistributions) {
  const ErrorModel m = ParseErrorModel(Model("  missized_to: {\"36\": {\"32\": 0.4, \"40\": 0.6}}\n"
                                             "  false_door_classes: {\"36\": 0.7, \"30\": 0.3}\n"),
                                       "m.yaml");
  EXPECT_DOUBLE_EQ(m.missized_to.at(DoorClass::k36).at(DoorClass::k40), 0.6);
  EXPECT_DOUBLE_EQ(m.false_door_classes.at(DoorClass::k30), 0.3);
}

TEST(ErrorModelFile, WrittenModelReadsBackTheSame) {
  ErrorModel m;
  // Quotes, a backslash before a non-ASCII byte, a tab and a newline: free text survives.
  m.source = "written \"here\" \\\xe9\t\\x41\n";
  m.door_correct = 0.9;
  m.door_missized = 0.07;
  m.door_missed = 0.03;
  m.wall_false_door = 0.05;
  m.missized_to[DoorClass::k36] = {{DoorClass::k40, 0.75}, {DoorClass::k32, 0.25}};
  m.false_door_classes = {{DoorClass::k30, 0.5}, {DoorClass::k40, 0.5}};
  const std::string text = FormatErrorModelYaml(m, "first line\nsecond line");
  EXPECT_EQ(text.rfind("# first line\n# second line\nerror_model:\n", 0), 0u) << text;
  const ErrorModel back = ParseErrorModel(text, "written.yaml");
  EXPECT_EQ(back.source, m.source);
  EXPECT_DOUBLE_EQ(back.door_correct, 0.9);
  EXPECT_DOUBLE_EQ(back.wall_false_door, 0.05);
  EXPECT_DOUBLE_EQ(back.missized_to.at(DoorClass::k36).at(DoorClass::k40), 0.75);
  EXPECT_DOUBLE_EQ(back.false_door_classes.at(DoorClass::k30), 0.5);
}

TEST(ErrorModelFile, DoorRatesMustSumToOne) {
  try {
    ParseErrorModel(Model("", "0.2"), "m.yaml");
    FAIL() << "accepted rates summing to 1.14";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "m.yaml");
    EXPECT_EQ(e.line(), 5);
    EXPECT_NE(e.reason().find("must be 1"), std::string::npos);
  }
}

TEST(ErrorModelFile, RateOutsideZeroOneIsRejected) {
  try {
    ParseErrorModel(Model("", "1.5"), "m.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "error_model.door_missed");
  }
}

TEST(ErrorModelFile, UnknownDoorClassIsRejectedWithItsKey) {
  try {
    ParseErrorModel(Model("  false_door_classes: {\"37\": 1.0}\n"), "m.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(e.key().find("37"), std::string::npos);
    EXPECT_NE(e.reason().find("unknown door class"), std::string::npos);
  }
}

TEST(ErrorModelFile, ReadsPerClassRatesAndLeafShares) {
  const ErrorModel m = ParseErrorModel(
      Model("  by_class:\n"
            "    \"36/36\": {correct: 0.5, missized: 0.45, missed: 0.05}\n"
            "  leaf_split: 0.6\n  leaf_sliver: 0.1\n  leaf_wall_before: 0.2\n"
            "  leaf_wall_after: 0.05\n"),
      "m.yaml");
  EXPECT_DOUBLE_EQ(m.by_class.at(DoorClass::k36_36).missized, 0.45);
  EXPECT_DOUBLE_EQ(m.leaf_wall_before, 0.2);
  // Resolved: the class's own rates, the others' from the overall ones.
  const map::Map corridor = testing::CorridorMap();
  const Confusion c = Resolve(m, map::MatchIndex(corridor));
  EXPECT_DOUBLE_EQ(c.class_correct[static_cast<int>(DoorClass::k36_36)], 0.5);
  EXPECT_DOUBLE_EQ(c.class_correct[static_cast<int>(DoorClass::k36)], 0.8367);
  // Written and read back.
  const ErrorModel back = ParseErrorModel(FormatErrorModelYaml(m, "x"), "back.yaml");
  EXPECT_DOUBLE_EQ(back.by_class.at(DoorClass::k36_36).missed, 0.05);
  EXPECT_DOUBLE_EQ(back.leaf_split, 0.6);
}

TEST(ErrorModelFile, ReadsTheRatesOfDoorsInARow) {
  const ErrorModel m =
      ParseErrorModel(Model("  by_class:\n"
                            "    \"36/36\": {correct: 0.5, missized: 0.45, missed: 0.05}\n"
                            "  in_row:\n"
                            "    wall_false_door: 0.4\n"
                            "    by_class:\n"
                            "      \"36/36\": {correct: 0.1, missized: 0.3, missed: 0.6}\n"),
                      "m.yaml");
  ASSERT_TRUE(m.in_row.has_value());
  EXPECT_DOUBLE_EQ(*m.in_row->wall_false_door, 0.4);
  EXPECT_DOUBLE_EQ(m.in_row->by_class.at(DoorClass::k36_36).missed, 0.6);
  // Resolved: in a row the row's rates, where it has none the class's; alone the class's.
  const Confusion c = Resolve(m, map::MatchIndex(testing::CorridorMap()));
  const int k36_36 = static_cast<int>(DoorClass::k36_36), k36 = static_cast<int>(DoorClass::k36);
  EXPECT_DOUBLE_EQ(c.Missed(k36_36, true), 0.6);
  EXPECT_DOUBLE_EQ(c.Missed(k36_36, false), 0.05);
  EXPECT_DOUBLE_EQ(c.Correct(k36, true), 0.8367);
  EXPECT_DOUBLE_EQ(c.FalseDoor(true), 0.4);
  EXPECT_DOUBLE_EQ(c.FalseDoor(false), 0.1591);
  // Written and read back.
  const ErrorModel back = ParseErrorModel(FormatErrorModelYaml(m, "x"), "back.yaml");
  ASSERT_TRUE(back.in_row.has_value());
  EXPECT_DOUBLE_EQ(*back.in_row->wall_false_door, 0.4);
  EXPECT_DOUBLE_EQ(back.in_row->by_class.at(DoorClass::k36_36).correct, 0.1);
  EXPECT_DOUBLE_EQ(back.by_class.at(DoorClass::k36_36).correct, 0.5);
  // Without in_row, doors in a row have the rates of every other door.
  const Confusion plain = Resolve(ErrorModel::Paper(), map::MatchIndex(testing::CorridorMap()));
  EXPECT_DOUBLE_EQ(plain.Missed(k36, true), plain.Missed(k36, false));
  EXPECT_DOUBLE_EQ(plain.FalseDoor(true), plain.FalseDoor(false));
}

TEST(ErrorModelFile, ReadsAFalseDoorRatePerInchAndWritesItBack) {
  const ErrorModel m = ParseErrorModel(Model("  wall_false_door_per_in: 0.002\n"), "m.yaml");
  ASSERT_TRUE(m.wall_false_door_per_in.has_value());
  EXPECT_DOUBLE_EQ(*m.wall_false_door_per_in, 0.002);
  const Confusion c = Resolve(m, map::MatchIndex(testing::CorridorMap()));
  EXPECT_NEAR(c.FalseDoorIn(100.0, false), 1.0 - std::exp(-0.2), 1e-12);
  EXPECT_TRUE(c.FalseDoorsChain());
  const ErrorModel back = ParseErrorModel(FormatErrorModelYaml(m, "x"), "back.yaml");
  EXPECT_EQ(back.wall_false_door_per_in, m.wall_false_door_per_in);
  // Without the key, per wall as before.
  const ErrorModel plain = ParseErrorModel(Model(""), "p.yaml");
  EXPECT_FALSE(plain.wall_false_door_per_in.has_value());
  EXPECT_FALSE(Resolve(plain, map::MatchIndex(testing::CorridorMap())).FalseDoorsChain());
  EXPECT_EQ(FormatErrorModelYaml(plain, "x").find("per_in"), std::string::npos);
  try {
    ParseErrorModel(Model("  wall_false_door_per_in: -0.001\n"), "bad.yaml");
    FAIL() << "accepted a negative rate";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.yaml:7"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("wall_false_door_per_in"), std::string::npos);
  }
}

TEST(ErrorModelFile, ReadsTheMostFalseDoorsOfAWallAndWritesItBack) {
  const ErrorModel m = ParseErrorModel(
      Model("  wall_false_door_per_in: 0.002\n  wall_false_doors_max: 2\n"), "m.yaml");
  ASSERT_TRUE(m.wall_false_doors_max.has_value());
  EXPECT_EQ(*m.wall_false_doors_max, 2);
  const Confusion c = Resolve(m, map::MatchIndex(testing::CorridorMap()));
  EXPECT_TRUE(c.AnotherFalseDoor(1));
  EXPECT_FALSE(c.AnotherFalseDoor(2));
  const ErrorModel back = ParseErrorModel(FormatErrorModelYaml(m, "x"), "back.yaml");
  EXPECT_EQ(back.wall_false_doors_max, m.wall_false_doors_max);
  // Without it, any number.
  const ErrorModel any = ParseErrorModel(Model("  wall_false_door_per_in: 0.002\n"), "a.yaml");
  EXPECT_FALSE(any.wall_false_doors_max.has_value());
  EXPECT_EQ(FormatErrorModelYaml(any, "x").find("doors_max"), std::string::npos);
  try {
    ParseErrorModel(Model("  wall_false_door_per_in: 0.002\n  wall_false_doors_max: 0\n"),
                    "bad.yaml");
    FAIL() << "accepted a wall that holds no false door";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 8);
    EXPECT_NE(e.key().find("wall_false_doors_max"), std::string::npos) << e.key();
  }
  try {
    ParseErrorModel(Model("  wall_false_doors_max: 2\n"), "bad.yaml");
    FAIL() << "accepted a most without a rate per inch";
  } catch (const InputError& e) {
    EXPECT_NE(e.reason().find("wall_false_door_per_in"), std::string::npos) << e.what();
  }
}

TEST(ErrorModelFile, ReadsTheRowWallsRatesByTheDoorBeforeAndWritesThemBack) {
  const ErrorModel m = ParseErrorModel(Model("  in_row:\n"
                                             "    wall_false_door: 0.44\n"
                                             "    wall_false_door_after_missed: 0.7\n"
                                             "    wall_false_door_after_seen: 0.06\n"),
                                       "m.yaml");
  ASSERT_TRUE(m.in_row && m.in_row->wall_false_door_after_missed);
  EXPECT_DOUBLE_EQ(*m.in_row->wall_false_door_after_missed, 0.7);
  EXPECT_DOUBLE_EQ(*m.in_row->wall_false_door_after_seen, 0.06);
  const ErrorModel back = ParseErrorModel(FormatErrorModelYaml(m, "x"), "back.yaml");
  ASSERT_TRUE(back.in_row && back.in_row->wall_false_door_after_seen);
  EXPECT_DOUBLE_EQ(*back.in_row->wall_false_door_after_missed, 0.7);
  EXPECT_DOUBLE_EQ(*back.in_row->wall_false_door_after_seen, 0.06);
  // Resolved: a wall of a row by the door before it where that is known; else, and on every
  // other wall, as before.
  const Confusion c = Resolve(m, map::MatchIndex(testing::CorridorMap()));
  EXPECT_DOUBLE_EQ(c.FalseDoorIn(40, true, Confusion::Before::kDoorMissed), 0.7);
  EXPECT_DOUBLE_EQ(c.FalseDoorIn(40, true, Confusion::Before::kDoorSeen), 0.06);
  EXPECT_DOUBLE_EQ(c.FalseDoorIn(40, true, Confusion::Before::kUnknown), 0.44);
  EXPECT_DOUBLE_EQ(c.FalseDoorIn(90, false, Confusion::Before::kDoorMissed), 0.1591);
}

TEST(ErrorModelFile, ReadsARowsMissedRatesByTheDoorBeforeAndWritesThemBack) {
  const ErrorModel m =
      ParseErrorModel(Model("  in_row:\n"
                            "    by_class:\n"
                            "      \"36\": {correct: 0.7, missized: 0.15, missed: 0.15}\n"
                            "    door_missed_after_missed: {\"36\": 0.4}\n"
                            "    door_missed_after_seen: {\"36\": 0.05}\n"),
                      "m.yaml");
  ASSERT_TRUE(m.in_row);
  EXPECT_DOUBLE_EQ(m.in_row->door_missed_after_missed.at(DoorClass::k36), 0.4);
  EXPECT_DOUBLE_EQ(m.in_row->door_missed_after_seen.at(DoorClass::k36), 0.05);
  const ErrorModel back = ParseErrorModel(FormatErrorModelYaml(m, "x"), "back.yaml");
  ASSERT_TRUE(back.in_row);
  EXPECT_EQ(back.in_row->door_missed_after_missed, m.in_row->door_missed_after_missed);
  EXPECT_EQ(back.in_row->door_missed_after_seen, m.in_row->door_missed_after_seen);
  // Resolved: a 36 in door of a row by the door before it, its reads sharing what is left;
  // not known, and every class the file does not list, as before.
  const Confusion c = Resolve(m, map::MatchIndex(testing::CorridorMap()));
  const int k36 = static_cast<int>(DoorClass::k36), k40 = static_cast<int>(DoorClass::k40);
  EXPECT_TRUE(c.row_missed_by_before);
  EXPECT_DOUBLE_EQ(c.RowMissed(k36, Confusion::Before::kDoorMissed), 0.4);
  EXPECT_DOUBLE_EQ(c.RowMissed(k36, Confusion::Before::kDoorSeen), 0.05);
  EXPECT_DOUBLE_EQ(c.RowMissed(k36, Confusion::Before::kUnknown), 0.15);
  EXPECT_DOUBLE_EQ(c.RowReadFactor(k36, Confusion::Before::kDoorMissed), 0.6 / 0.85);
  EXPECT_DOUBLE_EQ(c.RowReadFactor(k36, Confusion::Before::kDoorSeen), 0.95 / 0.85);
  EXPECT_DOUBLE_EQ(c.RowReadFactor(k36, Confusion::Before::kUnknown), 1.0);
  EXPECT_DOUBLE_EQ(c.RowMissed(k40, Confusion::Before::kDoorMissed), 0.0612);
  EXPECT_DOUBLE_EQ(c.RowReadFactor(k40, Confusion::Before::kDoorSeen), 1.0);
  // Without them a row's doors are missed alike whatever came before.
  const Confusion flat =
      Resolve(ParseErrorModel(Model(""), "m.yaml"), map::MatchIndex(testing::CorridorMap()));
  EXPECT_FALSE(flat.row_missed_by_before);
  EXPECT_DOUBLE_EQ(flat.RowMissed(k36, Confusion::Before::kDoorMissed), 0.0612);
}

TEST(ErrorModelFile, ARowsMissedRateByTheDoorBeforeAloneOrOutOfRangeIsRejected) {
  try {
    ParseErrorModel(Model("  in_row:\n"
                          "    wall_false_door: 0.44\n"
                          "    door_missed_after_seen: {\"36\": 0.05}\n"),
                    "m.yaml");
    FAIL() << "accepted door_missed_after_seen alone";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 9);
    EXPECT_NE(e.key().find("door_missed_after_seen"), std::string::npos) << e.key();
    EXPECT_NE(e.reason().find("go together"), std::string::npos) << e.reason();
  }
  try {
    ParseErrorModel(Model("  in_row:\n"
                          "    door_missed_after_missed: {\"36\": 1.4}\n"
                          "    door_missed_after_seen: {\"36\": 0.05}\n"),
                    "m.yaml");
    FAIL() << "accepted a rate of 1.4";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 8);
    EXPECT_NE(e.key().find("36"), std::string::npos) << e.key();
  }
  EXPECT_THROW(ParseErrorModel(Model("  in_row:\n"
                                     "    door_missed_after_missed: {\"37\": 0.4}\n"
                                     "    door_missed_after_seen: {\"36\": 0.05}\n"),
                               "m.yaml"),
               InputError);
  ErrorModel m = ErrorModel::Paper();
  m.in_row = ErrorModel::InRow{};
  m.in_row->door_missed_after_missed[DoorClass::k36] = 0.4;
  EXPECT_THROW(m.Validate(), std::invalid_argument);
  m.in_row->door_missed_after_seen[DoorClass::k36] = -0.1;
  EXPECT_THROW(m.Validate(), std::invalid_argument);
}

TEST(ErrorModelFile, ReadsTheWallsOverMissedDoorsAndWritesThemBack) {
  const ErrorModel m =
      ParseErrorModel(Model("  wall_over_missed_door: {bias_in: 3.5, sigma_in: 3.1}\n"), "m.yaml");
  ASSERT_TRUE(m.wall_over_missed_door);
  EXPECT_DOUBLE_EQ(m.wall_over_missed_door->bias_in, 3.5);
  EXPECT_DOUBLE_EQ(m.wall_over_missed_door->sigma_in, 3.1);
  const ErrorModel back = ParseErrorModel(FormatErrorModelYaml(m, "x"), "back.yaml");
  ASSERT_TRUE(back.wall_over_missed_door);
  EXPECT_DOUBLE_EQ(back.wall_over_missed_door->bias_in, 3.5);
  EXPECT_DOUBLE_EQ(back.wall_over_missed_door->sigma_in, 3.1);
  const Confusion c = Resolve(m, map::MatchIndex(testing::CorridorMap()));
  EXPECT_DOUBLE_EQ(c.missed_wall_bias_in, 3.5);
  EXPECT_DOUBLE_EQ(c.missed_wall_var_in2, 3.1 * 3.1);
  // Without the key: no shift, no spread.
  const Confusion none =
      Resolve(ParseErrorModel(Model(""), "m.yaml"), map::MatchIndex(testing::CorridorMap()));
  EXPECT_EQ(none.missed_wall_bias_in, 0.0);
  EXPECT_EQ(none.missed_wall_var_in2, 0.0);
}

TEST(ErrorModelFile, BadWallsOverMissedDoorsAreRejectedWithTheirKey) {
  try {
    ParseErrorModel(Model("  wall_over_missed_door: {bias_in: 3.5, sigma_in: -1}\n"), "m.yaml");
    FAIL() << "accepted a negative sigma";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 7);
    EXPECT_NE(e.key().find("wall_over_missed_door.sigma_in"), std::string::npos) << e.key();
  }
  EXPECT_THROW(
      ParseErrorModel(Model("  wall_over_missed_door: {bias_in: 30, sigma_in: 1}\n"), "m.yaml"),
      InputError);
  EXPECT_THROW(ParseErrorModel(Model("  wall_over_missed_door: {bias_in: 3}\n"), "m.yaml"),
               InputError);
  EXPECT_THROW(ParseErrorModel(Model("  wall_over_missed_door: 3\n"), "m.yaml"), InputError);
  ErrorModel m = ErrorModel::Paper();
  m.wall_over_missed_door = ErrorModel::WallOverMissedDoor{1.0, -2.0};
  EXPECT_THROW(m.Validate(), std::invalid_argument);
}

TEST(ErrorModelFile, OneRowWallRateByTheDoorBeforeWithoutTheOtherIsRejected) {
  try {
    ParseErrorModel(Model("  in_row:\n"
                          "    wall_false_door: 0.44\n"
                          "    wall_false_door_after_missed: 0.7\n"),
                    "m.yaml");
    FAIL() << "accepted wall_false_door_after_missed alone";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 9);
    EXPECT_NE(e.key().find("wall_false_door_after_missed"), std::string::npos) << e.key();
    EXPECT_NE(e.reason().find("go together"), std::string::npos) << e.reason();
  }
  EXPECT_THROW(ParseErrorModel(Model("  in_row:\n"
                                     "    wall_false_door_after_missed: 1.7\n"
                                     "    wall_false_door_after_seen: 0.1\n"),
                               "m.yaml"),
               InputError);
}

TEST(ErrorModelFile, BadRatesOfDoorsInARowAreRejectedWithTheirKey) {
  try {
    ParseErrorModel(Model("  in_row:\n    by_class:\n"
                          "      \"40\": {correct: 0.5, missized: 0.1, missed: 0.1}\n"),
                    "m.yaml");
    FAIL() << "accepted an in-row class row summing to 0.7";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 9);
    EXPECT_NE(e.key().find("in_row"), std::string::npos) << e.key();
    EXPECT_NE(e.reason().find("must be 1"), std::string::npos);
  }
  EXPECT_THROW(ParseErrorModel(Model("  in_row:\n    wall_false_door: 1.5\n"), "m.yaml"),
               InputError);
  EXPECT_THROW(ParseErrorModel(Model("  in_row:\n    walls: 0.5\n"), "m.yaml"), InputError);
}

TEST(ErrorModelFile, AClassRowThatDoesNotSumToOneIsRejectedOnItsLine) {
  try {
    ParseErrorModel(Model("  by_class:\n    \"32\": {correct: 0.5, missized: 0.1, missed: 0.1}\n"),
                    "m.yaml");
    FAIL() << "accepted a class row summing to 0.7";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 8);
    EXPECT_NE(e.key().find("32"), std::string::npos) << e.key();
    EXPECT_NE(e.reason().find("must be 1"), std::string::npos);
  }
}

TEST(ErrorModelFile, LeafSharesOverOneAreRejected) {
  try {
    ParseErrorModel(Model("  leaf_split: 0.7\n  leaf_wall_before: 0.4\n"), "m.yaml");
    FAIL() << "accepted leaf shares summing to 1.1";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "error_model.leaf_wall_before");
    EXPECT_NE(e.reason().find("more than 1"), std::string::npos);
  }
}

TEST(ErrorModelFile, UnknownKeyIsRejected) {
  EXPECT_THROW(ParseErrorModel(Model("  door_fuzzy: 0.1\n"), "m.yaml"), InputError);
}

TEST(ErrorModelResolve, MissizedDoorsGoToTheNeighbouringClassesEqually) {
  const map::Map m = testing::CorridorMap();
  const map::MatchIndex index(m);
  const Confusion c = Resolve(ErrorModel::Paper(), index);
  const int k36 = static_cast<int>(DoorClass::k36);
  EXPECT_DOUBLE_EQ(c.missized_to[k36][static_cast<int>(DoorClass::k32)], 0.5);
  EXPECT_DOUBLE_EQ(c.missized_to[k36][static_cast<int>(DoorClass::k40)], 0.5);
  // False doors follow the map's classes: 3 x 36, 2 x 40, 1 x 32.
  EXPECT_DOUBLE_EQ(c.false_class[k36], 0.5);
  EXPECT_DOUBLE_EQ(c.false_class[static_cast<int>(DoorClass::k32)], 1.0 / 6.0);
}

TEST(StudyConfigFile, ShippedConfigLoads) {
  const StudyConfig c = LoadStudyConfig(std::string(STICKREP_SOURCE_DIR) + "/configs/study.yaml");
  EXPECT_DOUBLE_EQ(c.speed_ftps, 2.6);
  EXPECT_DOUBLE_EQ(c.FrameTravelIn(), 6.24);
  ASSERT_EQ(c.relaxation_steps.size(), 2u);
  EXPECT_DOUBLE_EQ(c.relaxation_steps[1], 0.20);
}

TEST(StudyConfigFile, TheFalseDoorFitAndTheShortFirstPartAreOffUnlessAsked) {
  std::ifstream f(std::string(STICKREP_SOURCE_DIR) + "/configs/study.yaml");
  std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  EXPECT_FALSE(ParseStudyConfig(text, "study.yaml").bayes.false_door_fit);
  const std::string key = "    w2_over_missed_doors: true\n";
  const std::size_t at = text.find(key);
  ASSERT_NE(at, std::string::npos);
  text.insert(at + key.size(), "    false_door_fit: true\n");
  EXPECT_TRUE(ParseStudyConfig(text, "study.yaml").bayes.false_door_fit);
  EXPECT_FALSE(ParseStudyConfig(text, "study.yaml").bayes.first_part_in_noise);
  std::string in_noise = text;
  in_noise.insert(at + key.size(), "    first_part_in_noise: true\n");
  EXPECT_TRUE(ParseStudyConfig(in_noise, "study.yaml").bayes.first_part_in_noise);
  text.replace(text.find("false_door_fit: true"), 20, "false_door_fit: 3");
  EXPECT_THROW(ParseStudyConfig(text, "study.yaml"), InputError);
}

TEST(StudyConfigFile, MissingFileNamesIt) {
  try {
    LoadStudyConfig("/nonexistent/study.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "/nonexistent/study.yaml");
  }
}

TEST(ErrorModelFile, ReadsAndWritesTheMarkReads) {
  const ErrorModel m = ParseErrorModel(
      Model("  marks:\n"
            "    plain: {unknown: 0.2, plain: 0.7, window: 0.1}\n"
            "    poster: {unknown: 0.1, plain: 0.1, window: 0.2, poster: 0.6}\n"
            "    false_door: {unknown: 0.5, plain: 0.5}\n"),
      "m.yaml");
  ASSERT_TRUE(m.HasMarks());
  EXPECT_DOUBLE_EQ(m.mark_read.at(map::DoorMark::kPoster)[static_cast<int>(map::DoorMark::kPoster)],
                   0.6);
  const map::Map corridor = testing::CorridorMap();
  const Confusion c = Resolve(m, map::MatchIndex(corridor));
  EXPECT_DOUBLE_EQ(c.MarkLikelihood(map::DoorMark::kPlain, map::DoorMark::kPlain), 0.7);
  // A true mark the file leaves out (window) is read as false doors are.
  EXPECT_DOUBLE_EQ(c.MarkLikelihood(map::DoorMark::kUnknown, map::DoorMark::kWindow), 0.5);
  EXPECT_DOUBLE_EQ(c.FalseDoorMarkLikelihood(map::DoorMark::kPlain), 0.5);
  // A read never seen keeps a floor.
  EXPECT_GT(c.MarkLikelihood(map::DoorMark::kPoster, map::DoorMark::kPlain), 0.0);
  // The corridor's doors carry no pattern: a door the map does not survey is read as the
  // model's rows are, mixed equally (plain and poster here).
  EXPECT_DOUBLE_EQ(c.MarkLikelihood(map::DoorMark::kPlain, map::DoorMark::kUnknown), 0.4);
  EXPECT_DOUBLE_EQ(c.MarkLikelihood(map::DoorMark::kPoster, map::DoorMark::kUnknown), 0.3);
  const ErrorModel back = ParseErrorModel(FormatErrorModelYaml(m, "x"), "back.yaml");
  EXPECT_EQ(back.mark_read, m.mark_read);
  EXPECT_EQ(back.false_door_marks, m.false_door_marks);
  // Without a `marks:` block every read weighs 1.
  const Confusion none = Resolve(ErrorModel::Paper(), map::MatchIndex(corridor));
  EXPECT_DOUBLE_EQ(none.MarkLikelihood(map::DoorMark::kPoster, map::DoorMark::kPlain), 1.0);
}

TEST(ErrorModelFile, MissizedDoorsHaveTheirOwnMarkReads) {
  const ErrorModel m = ParseErrorModel(
      Model("  marks:\n"
            "    window: {plain: 0.1, window: 0.9}\n"
            "    false_door: {unknown: 0.5, plain: 0.5}\n"
            "  marks_missized:\n"
            "    window: {plain: 0.3, window: 0.3, poster: 0.4}\n"),
      "m.yaml");
  const map::Map corridor = testing::CorridorMap();
  const Confusion c = Resolve(m, map::MatchIndex(corridor));
  EXPECT_DOUBLE_EQ(c.MarkLikelihood(map::DoorMark::kWindow, map::DoorMark::kWindow, true), 0.9);
  EXPECT_DOUBLE_EQ(c.MarkLikelihood(map::DoorMark::kWindow, map::DoorMark::kWindow, false), 0.3);
  EXPECT_DOUBLE_EQ(c.MarkLikelihood(map::DoorMark::kPoster, map::DoorMark::kWindow, false), 0.4);
  const ErrorModel back = ParseErrorModel(FormatErrorModelYaml(m, "x"), "back.yaml");
  EXPECT_EQ(back.mark_read_missized, m.mark_read_missized);
  try {
    ParseErrorModel(Model("  marks_missized:\n    window: {window: 1}\n"), "m.yaml");
    FAIL() << "accepted mis-sized mark reads without a marks block";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "error_model.marks_missized");
  }
}

TEST(ErrorModelFile, BadMarkRowsAreRejectedWithTheirKey) {
  const auto reason = [](const std::string& marks) {
    try {
      ParseErrorModel(Model("  marks:\n" + marks), "m.yaml");
    } catch (const InputError& e) {
      return e.key() + ": " + e.reason();
    }
    return std::string("accepted");
  };
  EXPECT_NE(reason("    plain: {plain: 1}\n").find("false_door row"), std::string::npos);
  EXPECT_NE(reason("    glass: {plain: 1}\n    false_door: {plain: 1}\n").find("unknown true mark"),
            std::string::npos);
  EXPECT_NE(reason("    plain: {chalk: 1}\n    false_door: {plain: 1}\n").find("unknown mark"),
            std::string::npos);
  EXPECT_NE(reason("    plain: {plain: 0.5}\n    false_door: {plain: 1}\n").find("sum to 0.5"),
            std::string::npos);
  EXPECT_NE(reason("    plain: {plain: 1.5}\n    false_door: {plain: 1}\n").find("marks.plain.plain"),
            std::string::npos);
}

}  // namespace
}  // namespace stickrep::recovery
