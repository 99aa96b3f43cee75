// The live error model's counts held against a hand-made passage: which sensed door lay on
// which true edge, and how the leaves' marks were read (Table 6.8).
#include "whereami/edge_errors.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace stickrep::whereami {
namespace {

using map::DoorMark;

// W100, a 36 in door with a poster, W100, a 36 in door with a vision panel, W100.
map::Ring MarkedRing() {
  map::Ring ring;
  ring.id = "hall";
  ring.edges = {map::Edge::Wall(100), map::Edge::Door(map::DoorClass::k36, "poster"),
                map::Edge::Wall(100), map::Edge::Door(map::DoorClass::k36, "old_window"),
                map::Edge::Wall(100)};
  return ring;
}

map::SensedEdge Sensed(map::SymbolCode code, double metric_in, DoorMark mark) {
  map::SensedEdge e;
  e.code = code;
  e.metric_in = metric_in;
  e.mark = mark;
  return e;
}

// The robot's passage along the whole ring from its start, one reading per inch: the edge
// the optical axis is on at each.
std::vector<TruthSample> TruthEveryInch(const map::Ring& ring) {
  std::vector<double> ends;
  double at = 0.0;
  for (const map::Edge& e : ring.edges) ends.push_back(at += e.metric_in);
  std::vector<TruthSample> truth;
  for (double odo = 0.0; odo < ends.back(); odo += 1.0) {
    int edge = 0;
    while (odo >= ends[edge]) ++edge;
    truth.push_back({odo, edge});
  }
  return truth;
}

TEST(EdgeErrorsTest, CountsTheMarkReadOfEachTrueDoorAndOfFalseDoors) {
  const map::Ring ring = MarkedRing();
  const std::vector<TruthSample> truth = TruthEveryInch(ring);
  const map::SymbolCode door36 = map::DoorCode(map::DoorClass::k36);
  const map::SymbolCode door40 = map::DoorCode(map::DoorClass::k40);
  // The poster read, a false door read plain in the middle wall, the window door read as a
  // 40 in door and its mark not read.
  const std::vector<map::SensedEdge> sensed = {
      Sensed(map::kWallCode, 100, DoorMark::kUnknown), Sensed(door36, 36, DoorMark::kPoster),
      Sensed(map::kWallCode, 34, DoorMark::kUnknown),  Sensed(door36, 36, DoorMark::kPlain),
      Sensed(map::kWallCode, 30, DoorMark::kUnknown),  Sensed(door40, 36, DoorMark::kUnknown),
      Sensed(map::kWallCode, 100, DoorMark::kUnknown)};
  const std::vector<localizer::EdgeAssembler::Span> spans = {
      {0, 100}, {100, 136}, {136, 170}, {170, 206}, {206, 236}, {236, 272}, {272, 372}};
  const EdgeErrorCounts c = CompareWithTruth(ring, sensed, spans, truth, 0.0, 372.0);
  EXPECT_EQ(c.true_doors, 2);
  EXPECT_EQ(c.correct, 1);
  EXPECT_EQ(c.missized, 1);
  EXPECT_EQ(c.false_doors, 1);
  const auto at = [](DoorMark m) { return static_cast<int>(m); };
  EXPECT_EQ(c.mark_read[at(DoorMark::kPoster)][at(DoorMark::kPoster)], 1);
  EXPECT_EQ(c.mark_read_missized[at(DoorMark::kWindow)][at(DoorMark::kUnknown)], 1);
  EXPECT_EQ(c.mark_read[at(DoorMark::kWindow)][at(DoorMark::kUnknown)], 0);
  EXPECT_EQ(c.false_mark[at(DoorMark::kPlain)], 1);

  const recovery::ErrorModel m = c.ToModel("test");
  ASSERT_TRUE(m.HasMarks());
  // Only the poster was read with its class: one row; a mis-sized row needs its own row of
  // reads with the class right (the window has none).
  EXPECT_EQ(m.mark_read.size(), 1u);
  EXPECT_TRUE(m.mark_read_missized.empty());
  EXPECT_DOUBLE_EQ(m.mark_read.at(DoorMark::kPoster)[at(DoorMark::kPoster)], 1.0);
  ASSERT_TRUE(m.false_door_marks);
  EXPECT_DOUBLE_EQ((*m.false_door_marks)[at(DoorMark::kPlain)], 1.0);
  // The model written from the counts loads again.
  EXPECT_NO_THROW(recovery::ParseErrorModel(recovery::FormatErrorModelYaml(m, "t"), "t.yaml"));
}

// W100, D36, W46, D36/36, W46, D36, W100, D36, W100: three doors in a row, one alone.
TEST(EdgeErrorsTest, TalliesDoorsInARowApartFromDoorsAloneAndTheShortWallsBetweenThem) {
  map::Ring ring;
  ring.id = "row";
  ring.edges = {map::Edge::Wall(100), map::Edge::Door(map::DoorClass::k36),
                map::Edge::Wall(46),  map::Edge::Door(map::DoorClass::k36_36),
                map::Edge::Wall(46),  map::Edge::Door(map::DoorClass::k36),
                map::Edge::Wall(100), map::Edge::Door(map::DoorClass::k36),
                map::Edge::Wall(100)};
  const std::vector<TruthSample> truth = TruthEveryInch(ring);
  const map::SymbolCode door36 = map::DoorCode(map::DoorClass::k36);
  const map::SymbolCode door40 = map::DoorCode(map::DoorClass::k40);
  // The double door missed (its wall merged into one), a false 40 in door on the first
  // short wall, the three single doors read right.
  const std::vector<map::SensedEdge> sensed = {
      Sensed(map::kWallCode, 100, DoorMark::kUnknown), Sensed(door36, 36, DoorMark::kUnknown),
      Sensed(map::kWallCode, 2, DoorMark::kUnknown),   Sensed(door40, 40, DoorMark::kUnknown),
      Sensed(map::kWallCode, 122, DoorMark::kUnknown), Sensed(door36, 36, DoorMark::kUnknown),
      Sensed(map::kWallCode, 100, DoorMark::kUnknown), Sensed(door36, 36, DoorMark::kUnknown),
      Sensed(map::kWallCode, 100, DoorMark::kUnknown)};
  const std::vector<localizer::EdgeAssembler::Span> spans = {{0, 100},   {100, 136}, {136, 138},
                                                             {138, 178}, {178, 300}, {300, 336},
                                                             {336, 436}, {436, 472}, {472, 572}};
  const EdgeErrorCounts c = CompareWithTruth(ring, sensed, spans, truth, 0.0, 572.0);
  const auto cls = [](map::DoorClass k) { return static_cast<int>(k); };
  const EdgeErrorCounts::DoorTally& row36 = c.by_row[1][cls(map::DoorClass::k36)];
  const EdgeErrorCounts::DoorTally& row72 = c.by_row[1][cls(map::DoorClass::k36_36)];
  const EdgeErrorCounts::DoorTally& alone36 = c.by_row[0][cls(map::DoorClass::k36)];
  EXPECT_EQ(row36.passed, 2);
  EXPECT_EQ(row36.correct, 2);
  EXPECT_EQ(row72.passed, 1);
  EXPECT_EQ(row72.missed, 1);
  EXPECT_EQ(alone36.passed, 1);
  EXPECT_EQ(alone36.correct, 1);
  EXPECT_EQ(c.by_row[0][cls(map::DoorClass::k36_36)].passed, 0);
  // By the door before across a short wall: the double door after the first 36 in door
  // (seen) was missed, the 36 in door after the double door (missed) was read; the first
  // door and the one after the 100 in wall have none.
  const auto& after_seen = c.row_by_before[0];
  const auto& after_missed = c.row_by_before[1];
  EXPECT_EQ(after_seen[cls(map::DoorClass::k36_36)].passed, 1);
  EXPECT_EQ(after_seen[cls(map::DoorClass::k36_36)].missed, 1);
  EXPECT_EQ(after_seen[cls(map::DoorClass::k36)].passed, 0);
  EXPECT_EQ(after_missed[cls(map::DoorClass::k36)].passed, 1);
  EXPECT_EQ(after_missed[cls(map::DoorClass::k36)].correct, 1);
  EXPECT_EQ(after_missed[cls(map::DoorClass::k36_36)].passed, 0);
  // The two 46 in walls lie between doors; the 100 in wall between the last two doors is
  // not short (the first and the last wall are not passed whole).
  EXPECT_EQ(c.walls_by_row[1].walls, 2);
  EXPECT_EQ(c.walls_by_row[1].false_doors, 1);
  EXPECT_EQ(c.walls_by_row[0].walls, 1);
  EXPECT_EQ(c.walls_by_row[0].false_doors, 0);
  EXPECT_EQ(c.walls_by_row[0].wall_in, 100.0);
  EXPECT_EQ(c.walls_by_row[1].wall_in, 92.0);
  EXPECT_EQ(c.false_doors, 1);
  // By length: the two 46 in walls (one false door) and the 100 in one.
  EXPECT_EQ(c.walls_by_length[0].walls, 2);
  EXPECT_EQ(c.walls_by_length[0].false_doors, 1);
  EXPECT_EQ(c.walls_by_length[1].walls, 1);
  EXPECT_EQ(c.walls_by_length[1].false_doors, 0);
  // The tallies add up over runs.
  EdgeErrorCounts sum = c;
  sum.Add(c);
  EXPECT_EQ(sum.by_row[1][cls(map::DoorClass::k36)].correct, 4);
  EXPECT_EQ(sum.walls_by_row[1].false_doors, 2);
  // As a model: each class's rates (3 of 3 single doors right, the double door missed,
  // shrunk towards 3 of 4 doors right by 20 doors' worth), split into the doors in a row
  // and alone, each shrunk towards its class's; the short walls' false doors apart.
  const recovery::ErrorModel m = c.ToModel("test");
  ASSERT_TRUE(m.in_row.has_value());
  const double k = EdgeErrorCounts::kClassPriorDoors;
  const double class36 = (3 + k * 0.75) / (3 + k), class72 = (0 + k * 0.75) / (1 + k);
  EXPECT_NEAR(m.in_row->by_class.at(map::DoorClass::k36).correct, (2 + k * class36) / (2 + k),
              1e-12);
  EXPECT_NEAR(m.by_class.at(map::DoorClass::k36).correct, (1 + k * class36) / (1 + k), 1e-12);
  EXPECT_NEAR(m.in_row->by_class.at(map::DoorClass::k36_36).correct, k * class72 / (1 + k), 1e-12);
  // Never seen alone: its class's rates.
  EXPECT_NEAR(m.by_class.at(map::DoorClass::k36_36).correct, class72, 1e-12);
  EXPECT_NEAR(*m.in_row->wall_false_door, (1 + k / 3) / (2 + k), 1e-12);
  // The missed rates by the door before, each shrunk towards the class's in a row.
  const double row36_missed = m.in_row->by_class.at(map::DoorClass::k36).missed;
  const double row72_missed = m.in_row->by_class.at(map::DoorClass::k36_36).missed;
  EXPECT_NEAR(m.in_row->door_missed_after_missed.at(map::DoorClass::k36),
              k * row36_missed / (1 + k), 1e-12);
  EXPECT_NEAR(m.in_row->door_missed_after_seen.at(map::DoorClass::k36), row36_missed, 1e-12);
  EXPECT_NEAR(m.in_row->door_missed_after_seen.at(map::DoorClass::k36_36),
              (1 + k * row72_missed) / (1 + k), 1e-12);
  EXPECT_NEAR(m.wall_false_door, (0 + k / 3) / (1 + k), 1e-12);
  // Per inch: the other walls' false doors over their length (none on 100 in).
  ASSERT_TRUE(m.wall_false_door_per_in.has_value());
  EXPECT_EQ(*m.wall_false_door_per_in, 0.0);
  EXPECT_NO_THROW(m.Validate());
}

TEST(EdgeErrorsTest, FalseDoorsPerInchAreCountedOverTheLengthOfTheWallsOutsideRows) {
  // W100, D36, W300, D36, W200, D36, W100: two false doors on the 300 in wall, one on the
  // 200 in wall.
  map::Ring ring;
  ring.id = "long";
  ring.edges = {map::Edge::Wall(100), map::Edge::Door(map::DoorClass::k36),
                map::Edge::Wall(300), map::Edge::Door(map::DoorClass::k36),
                map::Edge::Wall(200), map::Edge::Door(map::DoorClass::k36),
                map::Edge::Wall(100)};
  const std::vector<TruthSample> truth = TruthEveryInch(ring);
  const map::SymbolCode door36 = map::DoorCode(map::DoorClass::k36);
  const map::SymbolCode door30 = map::DoorCode(map::DoorClass::k30);
  const auto wall = [](double in) { return Sensed(map::kWallCode, in, DoorMark::kUnknown); };
  const auto door = [](map::SymbolCode code, double in) {
    return Sensed(code, in, DoorMark::kUnknown);
  };
  const std::vector<map::SensedEdge> sensed = {
      wall(100),        door(door36, 36), wall(60),         door(door30, 30), wall(80),
      door(door30, 30), wall(100),        door(door36, 36), wall(120),        door(door30, 30),
      wall(50),         door(door36, 36), wall(100)};
  const std::vector<localizer::EdgeAssembler::Span> spans = {
      {0, 100},   {100, 136}, {136, 196}, {196, 226}, {226, 306}, {306, 336}, {336, 436},
      {436, 472}, {472, 592}, {592, 622}, {622, 672}, {672, 708}, {708, 808}};
  const EdgeErrorCounts c = CompareWithTruth(ring, sensed, spans, truth, 0.0, 808.0);
  EXPECT_EQ(c.walls_by_row[0].walls, 2);
  EXPECT_EQ(c.walls_by_row[0].false_doors, 3);
  EXPECT_EQ(c.walls_by_row[0].wall_in, 500.0);
  EXPECT_EQ(c.walls_by_length[3].walls, 1);  // 240-480 in: the 300 in wall
  EXPECT_EQ(c.walls_by_length[3].false_doors, 2);
  EXPECT_EQ(c.walls_by_length[2].false_doors, 1);  // 120-240 in: the 200 in wall
  // The walls outside rows by their false doors: the 200 in wall held one, the 300 in two.
  EXPECT_EQ(c.walls_by_false_doors, (std::array<long, 5>{0, 1, 1, 0, 0}));
  const recovery::ErrorModel m = c.ToModel("test");
  ASSERT_TRUE(m.wall_false_door_per_in.has_value());
  EXPECT_DOUBLE_EQ(*m.wall_false_door_per_in, 3.0 / 500.0);
  EXPECT_NO_THROW(m.Validate());
}

TEST(EdgeErrorsTest, RunsWithoutAnyDoorGiveNoMarkRows) {
  EXPECT_FALSE(EdgeErrorCounts{}.ToModel("empty").HasMarks());
}

// A row: W100, D36, a 46 in panel, a 36/36, a panel, D36, a panel, D36, W100; read with the
// double door missed and the panel beyond it read as a 40 in door.
TEST(EdgeErrorsTest, CountsTheRowWallsFalseDoorsByTheDoorsBesideThemAndTheWallsLengthErrors) {
  map::Ring ring;
  ring.id = "row";
  using map::DoorClass;
  using map::Edge;
  ring.edges = {
      Edge::Wall(100), Edge::Door(DoorClass::k36), Edge::Wall(46), Edge::Door(DoorClass::k36_36),
      Edge::Wall(46),  Edge::Door(DoorClass::k36), Edge::Wall(46), Edge::Door(DoorClass::k36),
      Edge::Wall(100)};
  const std::vector<TruthSample> truth = TruthEveryInch(ring);
  const map::SymbolCode door36 = map::DoorCode(DoorClass::k36);
  const map::SymbolCode door40 = map::DoorCode(DoorClass::k40);
  const std::vector<map::SensedEdge> sensed = {
      Sensed(map::kWallCode, 100, DoorMark::kUnknown), Sensed(door36, 36, DoorMark::kUnknown),
      Sensed(map::kWallCode, 121, DoorMark::kUnknown), Sensed(door40, 40, DoorMark::kUnknown),
      Sensed(map::kWallCode, 3, DoorMark::kUnknown),   Sensed(door36, 36, DoorMark::kUnknown),
      Sensed(map::kWallCode, 46, DoorMark::kUnknown),  Sensed(door36, 36, DoorMark::kUnknown),
      Sensed(map::kWallCode, 100, DoorMark::kUnknown)};
  const std::vector<localizer::EdgeAssembler::Span> spans = {{0, 100},   {100, 136}, {136, 257},
                                                             {257, 297}, {297, 300}, {300, 336},
                                                             {336, 382}, {382, 418}, {418, 518}};
  const EdgeErrorCounts c = CompareWithTruth(ring, sensed, spans, truth, 0.0, 518.0);
  EXPECT_EQ(c.missed, 1);
  EXPECT_EQ(c.false_doors, 1);
  // [short][before missed][after missed]: the panel before the missed door held none, the
  // one after it held the false door, the one between two doors seen none.
  const auto& rows = c.walls_by_missed[1];
  EXPECT_EQ(rows[0][1].walls, 1);
  EXPECT_EQ(rows[0][1].false_doors, 0);
  EXPECT_EQ(rows[1][0].walls, 1);
  EXPECT_EQ(rows[1][0].false_doors, 1);
  EXPECT_EQ(rows[0][0].walls, 1);
  EXPECT_EQ(rows[0][0].false_doors, 0);
  EXPECT_EQ(c.walls_by_missed[0][0][0].walls, 0);
  const recovery::ErrorModel m = c.ToModel("test");
  ASSERT_TRUE(m.in_row && m.in_row->wall_false_door_after_missed);
  EXPECT_GT(*m.in_row->wall_false_door_after_missed, *m.in_row->wall_false_door);
  EXPECT_LT(*m.in_row->wall_false_door_after_seen, *m.in_row->wall_false_door);
  // The walls' lengths: the wall over the missed door is 3 in longer than the panel and the
  // door (its end is 3 in into the next panel, within the 8 in of a node); the panel between
  // two doors seen is read exactly. The 3 in after the false door has both ends by one node,
  // the first and the last wall are not counted.
  ASSERT_EQ(c.wall_residuals.size(), 2u);
  EXPECT_TRUE(c.wall_residuals[0].over_missed);
  EXPECT_NEAR(c.wall_residuals[0].error_in, 3.0, 1e-9);
  EXPECT_NEAR(c.wall_residuals[0].true_in, 118.0, 1e-9);
  EXPECT_FALSE(c.wall_residuals[1].over_missed);
  EXPECT_EQ(c.wall_residuals[1].start, EdgeErrorCounts::WallEnd::kDoorRight);
  EXPECT_EQ(c.wall_residuals[1].end, EdgeErrorCounts::WallEnd::kDoorRight);
  EXPECT_NEAR(c.wall_residuals[1].error_in, 0.0, 1e-9);
  EXPECT_EQ(c.wall_residuals[0].missed_doors, 1);
  EXPECT_EQ(c.wall_residuals[1].missed_doors, 0);
}

// ErrorModel::wall_over_missed_door by moments: per missed door the mean error, and the
// spread beyond the matcher's sigma of each wall.
TEST(EdgeErrorsTest, WallsOverMissedDoorsGiveTheirShiftAndSpreadPerMissedDoor) {
  recovery::SensingNoise noise = recovery::SensingNoise::None();  // the matcher's sigma: 1 in
  EdgeErrorCounts c;
  const auto wall = [&](double error, int missed) {
    EdgeErrorCounts::WallResidual r;
    r.error_in = error;
    r.true_in = 100.0;
    r.missed_doors = missed;
    r.over_missed = missed > 0;
    c.wall_residuals.push_back(r);
  };
  for (int i = 0; i < EdgeErrorCounts::kMinMissedWalls - 1; ++i) wall(i % 2 ? 1.0 : 7.0, 1);
  wall(0.0, 0);
  wall(50.0, 0);  // walls over no missed door do not count
  EXPECT_FALSE(c.ToModel("test", &noise).wall_over_missed_door) << "too few walls";
  EXPECT_FALSE(c.ToModel("test").wall_over_missed_door) << "without the matcher's noise";
  wall(5.0, 2);
  // 19 walls over one door (10 at +7, 9 at +1) and one over two at +5: 84 in over 21 doors,
  // 4 in per door; the residuals 3 (x10), -3 (x9) and -3, less 1 in^2 each of the 20 walls:
  // (180 - 20) / 21 in^2 per door.
  const recovery::ErrorModel m = c.ToModel("test", &noise);
  ASSERT_TRUE(m.wall_over_missed_door);
  EXPECT_NEAR(m.wall_over_missed_door->bias_in, 84.0 / 21.0, 1e-9);
  EXPECT_NEAR(m.wall_over_missed_door->sigma_in, std::sqrt(160.0 / 21.0), 1e-9);
}

}  // namespace
}  // namespace stickrep::whereami
