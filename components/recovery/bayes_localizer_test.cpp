#include "recovery/bayes_localizer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "recovery/test_support.h"

namespace stickrep::recovery {
namespace {

using map::DoorClass;
using testing::Door;
using testing::Wall;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The filter's model of `em` on `index`, without sensing noise, reporting at `threshold`.
BayesModel ModelOf(const map::MatchIndex& index, const ErrorModel& em, double threshold) {
  BayesModel m;
  m.confusion = Resolve(em, index);
  m.noise = SensingNoise{};
  m.settings.threshold = threshold;
  return m;
}

BayesLocalizer MakeLocalizer(const map::MatchIndex& index, const ErrorModel& em,
                             double threshold = 0.99, int confirm_edges = 0,
                             bool false_door_fit = false) {
  BayesModel m = ModelOf(index, em, threshold);
  m.settings.confirm_edges = confirm_edges;
  m.settings.false_door_fit = false_door_fit;
  return BayesLocalizer(index, m);
}

class BayesLocalizerTest : public ::testing::Test {
 protected:
  BayesLocalizer Make(const ErrorModel& em, double threshold = 0.99, int confirm_edges = 0) {
    return MakeLocalizer(index_, em, threshold, confirm_edges);
  }
  map::Map map_ = testing::CorridorMap();
  map::MatchIndex index_{map_};
};

TEST_F(BayesLocalizerTest, EmptyBeforeTheFirstEdge) {
  BayesLocalizer b = Make(ErrorModel::Paper());
  EXPECT_EQ(b.status(), RecoveryStatus::kEmpty);
  EXPECT_TRUE(b.Top(3).empty());
}

TEST_F(BayesLocalizerTest, ExactSequenceEndsAtTheTruth) {
  BayesLocalizer b = Make(ErrorModel::Paper());
  b.Add(Wall(150, kNaN, true));  // inside the 200 in wall
  b.Add(Door(DoorClass::k40));
  b.Add(Wall(90));
  b.Add(Door(DoorClass::k36));
  b.Add(Wall(75));
  EXPECT_EQ(b.best().edge, 10);
  EXPECT_EQ(b.best().dir, +1);
  EXPECT_EQ(b.status(), RecoveryStatus::kLocalized);
}

TEST_F(BayesLocalizerTest, ReversalCarriesTheBeliefToTheWayBack) {
  BayesLocalizer b = Make(ErrorModel::Paper());
  b.Add(Wall(150, kNaN, true));
  b.Add(Door(DoorClass::k40));
  b.Add(Wall(90));
  b.Add(Door(DoorClass::k36));
  b.Add(Wall(75));
  ASSERT_EQ(b.best().edge, 10);
  // The robot turns back inside edge 11: the place becomes (11, backward), and the part
  // of edge 11 it sees again is not weighed.
  b.Reverse();
  EXPECT_EQ(b.best().edge, 11);
  EXPECT_EQ(b.best().dir, -1);
  EXPECT_EQ(b.status(), RecoveryStatus::kLocalized);
  b.Add(Wall(30, kNaN, true));
  EXPECT_EQ(b.edges(), 5);
  b.Add(Wall(75));
  b.Add(Door(DoorClass::k36));
  EXPECT_EQ(b.edges(), 7);
  EXPECT_EQ(b.best().edge, 9);
  EXPECT_EQ(b.best().dir, -1);
  EXPECT_GT(b.best().probability, 0.99);
}

TEST_F(BayesLocalizerTest, ReversalFarPastTheLastEdgeIsPlacedByTheDistance) {
  BayesLocalizer b = Make(ErrorModel::Paper());
  b.Add(Wall(150, kNaN, true));
  b.Add(Door(DoorClass::k40));
  b.Add(Wall(90));
  ASSERT_EQ(b.best().edge, 8);
  // The robot went 76 in past wall 8 seeing nothing: across door 9 (missed) into the 75 in
  // wall 10, and turned back there.
  b.Reverse(76.0);
  EXPECT_EQ(b.best().edge, 10);
  EXPECT_EQ(b.best().dir, -1);
  b.Add(Wall(40, kNaN, true));  // the part of wall 10 seen again: not weighed
  b.Add(Door(DoorClass::k36));  // door 9, seen this time
  b.Add(Wall(90));
  b.Add(Door(DoorClass::k40));
  EXPECT_EQ(b.best().edge, 7);
  EXPECT_EQ(b.best().dir, -1);
  EXPECT_GT(b.best().probability, 0.99);
  // Without the distance the belief turns back in wall 8's next edge, door 9, and the
  // same sightings fit worse.
  BayesLocalizer c = Make(ErrorModel::Paper());
  c.Add(Wall(150, kNaN, true));
  c.Add(Door(DoorClass::k40));
  c.Add(Wall(90));
  c.Reverse();
  EXPECT_EQ(c.best().edge, 9);
  c.Add(Wall(40, kNaN, true));
  c.Add(Door(DoorClass::k36));
  c.Add(Wall(90));
  c.Add(Door(DoorClass::k40));
  EXPECT_LT(c.PoseProbability(7, -1), b.best().probability);
}

TEST_F(BayesLocalizerTest, ReversalWithinTheNextEdgeIsTheSameWithOrWithoutTheDistance) {
  BayesLocalizer with = Make(ErrorModel::Paper());
  BayesLocalizer without = Make(ErrorModel::Paper());
  for (BayesLocalizer* b : {&with, &without}) {
    b->Add(Wall(150, kNaN, true));
    b->Add(Door(DoorClass::k40));
    b->Add(Wall(90));
    b->Add(Door(DoorClass::k36));
  }
  // 40 in into the 75 in wall 10.
  with.Reverse(40.0);
  without.Reverse();
  EXPECT_EQ(with.best().edge, without.best().edge);
  EXPECT_EQ(with.best().dir, without.best().dir);
  EXPECT_EQ(with.best().edge, 10);
}

TEST_F(BayesLocalizerTest, ConfirmationWaitsForTheThresholdToHoldOverMoreEdges) {
  BayesLocalizer now = Make(ErrorModel::Paper());
  BayesLocalizer later = Make(ErrorModel::Paper(), 0.99, 1);
  int first_now = -1, first_later = -1;
  const std::vector<map::SensedEdge> edges = {Wall(150, kNaN, true), Door(DoorClass::k40),
                                              Wall(90), Door(DoorClass::k36), Wall(75)};
  for (int i = 0; i < static_cast<int>(edges.size()); ++i) {
    now.Add(edges[i]);
    later.Add(edges[i]);
    if (first_now < 0 && now.status() == RecoveryStatus::kLocalized) first_now = i;
    if (first_later < 0 && later.status() == RecoveryStatus::kLocalized) first_later = i;
  }
  ASSERT_GE(first_now, 0);
  EXPECT_EQ(first_later, first_now + 1);
  EXPECT_EQ(later.best().edge, now.best().edge);
}

// The corridor: W120 D36 W60 D36 W60 D32 W200 D40 W90 D36 W75 D40 W150, corners at its ends.
TEST_F(BayesLocalizerTest, SilenceWithdrawsThePlacesWhoseNextDoorShouldHaveComeByNow) {
  BayesLocalizer b = Make(ErrorModel::Paper());
  b.Add(Wall(50, kNaN, true));
  b.Add(Door(DoorClass::k36));
  // Doors 1, 3 and 9 either way fit; after all but door 1 travelled backward (W120 to the
  // corner) the map has a door or corner within 90 in.
  const double alone = b.PoseProbability(1, -1);
  ASSERT_LT(alone, 0.9);
  b.SetSilence(0.0);
  EXPECT_NEAR(b.PoseProbability(1, -1), alone, 1e-4);
  b.SetSilence(105.0);
  EXPECT_EQ(b.best().edge, 1);
  EXPECT_EQ(b.best().dir, -1);
  const double after = b.PoseProbability(1, -1);
  EXPECT_GT(after, 2.0 * alone);
  double sum = 0.0;
  for (const PoseBelief& p : b.Top(1000)) sum += p.probability;
  EXPECT_NEAR(sum, 1.0, 1e-9);
  // Past that place's corner too: silence cannot explain it either.
  b.SetSilence(400.0);
  EXPECT_LT(b.PoseProbability(1, -1), after);
  // The next edge ends the silence: the belief is the edges' again.
  b.Add(Wall(118));
  EXPECT_EQ(b.silent_in(), 0.0);
}

TEST_F(BayesLocalizerTest, ConfirmationBySilenceDeclaresOnlyAPlaceWhoseNextDoorIsStillAhead) {
  BayesModel m;
  m.confusion = Resolve(ErrorModel::Paper(), index_);
  m.settings.threshold = 0.6;
  m.settings.confirm_silent_in = 60.0;
  BayesLocalizer b(index_, m), c(index_, m);
  BayesLocalizer now = Make(ErrorModel::Paper(), 0.6);
  // Up to the edge at which the place first holds the threshold.
  for (const map::SensedEdge& e : {Wall(40, kNaN, true), Door(DoorClass::k36), Wall(60),
                                   Door(DoorClass::k32), Wall(200)}) {
    b.Add(e);
    c.Add(e);
    now.Add(e);
    if (now.status() == RecoveryStatus::kLocalized) break;
  }
  ASSERT_EQ(now.status(), RecoveryStatus::kLocalized);
  const int next = index_.Step(now.best().edge, now.best().dir);
  ASSERT_GE(next, 0);
  ASSERT_GT(index_.metric(next), 70.0);  // the place's next edge runs on past 60 in
  EXPECT_EQ(b.status(), RecoveryStatus::kAmbiguous);  // held the threshold, not confirmed
  b.SetSilence(30.0);
  EXPECT_EQ(b.status(), RecoveryStatus::kAmbiguous);
  b.SetSilence(60.0);
  EXPECT_EQ(b.status(), RecoveryStatus::kLocalized);
  EXPECT_EQ(b.best().edge, now.best().edge);
  // Long past that edge and whatever follows it: the place is withdrawn, not declared.
  c.SetSilence(600.0);
  EXPECT_EQ(c.status(), RecoveryStatus::kAmbiguous);
}

TEST_F(BayesLocalizerTest, PosteriorSumsToOneAndTopIsSorted) {
  BayesLocalizer b = Make(ErrorModel::Paper());
  b.Add(Door(DoorClass::k36));
  b.Add(Wall(60));
  double sum = 0;
  for (int g = 0; g < index_.EdgeCount(); ++g) {
    sum += b.PoseProbability(g, +1) + b.PoseProbability(g, -1);
  }
  EXPECT_NEAR(sum, 1.0, 1e-9);
  const auto top = b.Top(4);
  ASSERT_GE(top.size(), 2u);
  for (std::size_t i = 1; i < top.size(); ++i) {
    EXPECT_GE(top[i - 1].probability, top[i].probability);
  }
  EXPECT_EQ(b.status(), RecoveryStatus::kAmbiguous);
}

TEST_F(BayesLocalizerTest, ExplainsAFalseDoorThatSplitsAWall) {
  BayesLocalizer b = Make(ErrorModel::Paper());
  b.Add(Wall(150, kNaN, true));
  b.Add(Door(DoorClass::k40));
  b.Add(Wall(30));
  b.Add(Door(DoorClass::k32));  // false: 30 + 32 + 28 = the 90 in wall
  b.Add(Wall(28));
  b.Add(Door(DoorClass::k36));
  b.Add(Wall(75));
  EXPECT_EQ(b.best().edge, 10);
  EXPECT_EQ(b.best().dir, +1);
  EXPECT_GT(b.best().probability, 0.9);
}

// With best_with_neighbours the best place is the (edge, direction) whose belief with its
// two ring neighbours' (the same direction) is the most, and that sum is its probability.
TEST_F(BayesLocalizerTest, WithItsNeighboursTheBestPlaceHoldsTheBeliefAroundIt) {
  BayesModel m = ModelOf(index_, ErrorModel::Paper(), 0.995);
  m.settings.best_with_neighbours = true;
  BayesLocalizer b(index_, m);
  BayesLocalizer single = MakeLocalizer(index_, ErrorModel::Paper(), 0.995);
  // The 36 in door (edge 9) may also be a false door inside the 90 in wall before it: the
  // filter holds a little belief on that wall (edge 8) as well.
  for (BayesLocalizer* f : {&b, &single}) {
    f->Add(Wall(150, kNaN, true));
    f->Add(Door(DoorClass::k40));
    f->Add(Wall(90));
    f->Add(Door(DoorClass::k36));
  }
  const auto window = [&](int g, int dir) {
    double p = b.PoseProbability(g, dir);
    for (int step : {-1, +1}) {
      const int n = index_.Step(g, step);
      if (n >= 0) p += b.PoseProbability(n, dir);
    }
    return p;
  };
  EXPECT_EQ(b.best().edge, 9);
  EXPECT_EQ(b.best().dir, +1);
  EXPECT_NEAR(b.best().probability, window(9, +1), 1e-12);
  EXPECT_GT(b.PoseProbability(8, +1), 0.001);
  // The filters are the same; only the best place is read differently. The place alone is
  // under the threshold, with its neighbours it is over.
  EXPECT_NEAR(b.PoseProbability(9, +1), single.best().probability, 1e-12);
  EXPECT_LT(single.best().probability, 0.995);
  EXPECT_EQ(single.status(), RecoveryStatus::kAmbiguous);
  EXPECT_GE(b.best().probability, 0.995);
  EXPECT_EQ(b.status(), RecoveryStatus::kLocalized);
}

// A place is published only where the belief peaks: walls 8 and 10 either side of a door
// the filter is split on (was it missed?) do not make the door between them the place.
TEST_F(BayesLocalizerTest, WithItsNeighboursTheBestPlaceIsWhereTheBeliefPeaks) {
  BayesModel m = ModelOf(index_, ErrorModel::Paper(), 0.99);
  m.settings.best_with_neighbours = true;
  BayesLocalizer b(index_, m);
  b.Add(Wall(150, kNaN, true));
  b.Add(Door(DoorClass::k40));
  b.Add(Wall(150));
  EXPECT_GT(b.PoseProbability(8, +1) + b.PoseProbability(10, +1), 0.7);
  EXPECT_EQ(b.best().edge, 10);
}

// A corridor with one long wall (edge 2, 600 in) and short ones:
//   0 W120 1 D36 2 W600 3 D40 4 W120 5 D32 6 W200 7 D30 8 W100 9 D36 10 W80 11 D40 12 W150
map::Map CorridorWithALongWall() {
  using map::Edge;
  return testing::ClosedCorridor(
      {Edge::Wall(120), Edge::Door(DoorClass::k36), Edge::Wall(600), Edge::Door(DoorClass::k40),
       Edge::Wall(120), Edge::Door(DoorClass::k32), Edge::Wall(200), Edge::Door(DoorClass::k30),
       Edge::Wall(100), Edge::Door(DoorClass::k36), Edge::Wall(80), Edge::Door(DoorClass::k40),
       Edge::Wall(150)},
      {0, 12});
}

// The belief in the truth after the long wall is sensed with two false doors in it, 150 +
// 30 + 170 + 32 + 218 in, and the walk goes on to the 40 in door and the wall after it.
double TruthAfterTwoFalseDoors(const map::MatchIndex& index, const ErrorModel& em) {
  BayesLocalizer b = MakeLocalizer(index, em);
  for (const map::SensedEdge& e :
       {Wall(100, kNaN, true), Door(DoorClass::k36), Wall(150), Door(DoorClass::k30), Wall(170),
        Door(DoorClass::k32), Wall(218), Door(DoorClass::k40), Wall(120)}) {
    b.Add(e);
  }
  return b.PoseProbability(4, +1);
}

TEST(BayesLocalizerFalseDoorTest, ARatePerInchExplainsTwoFalseDoorsInALongWall) {
  const map::Map map = CorridorWithALongWall();
  const map::MatchIndex index(map);
  const ErrorModel per_wall = ErrorModel::Paper();
  ErrorModel per_inch = per_wall;
  // About the paper's 0.16 per wall on a 120 in wall; 0.6 on the 600 in one.
  per_inch.wall_false_door_per_in = 0.0015;
  per_inch.Validate();
  const Confusion cf = Resolve(per_inch, index);
  EXPECT_NEAR(cf.FalseDoorIn(120.0, false), 1.0 - std::exp(-0.18), 1e-12);
  EXPECT_GT(cf.FalseDoorIn(600.0, false), 3.0 * cf.FalseDoorIn(120.0, false));
  EXPECT_EQ(Resolve(per_wall, index).FalseDoorIn(600.0, false), per_wall.wall_false_door);

  // One false door per wall at most: the second is one of the outliers, and the truth is
  // not sure. With the rate per inch the rest of the wall holds the second.
  const double before = TruthAfterTwoFalseDoors(index, per_wall);
  const double after = TruthAfterTwoFalseDoors(index, per_inch);
  EXPECT_GT(after, 0.9);
  EXPECT_GT(after, before + 0.2) << "before " << before << ", after " << after;
}

// The most false doors one wall holds: with one, the second false door in the long wall is
// an outlier again, as with the rate per wall; with two, the rest of the wall holds it.
TEST(BayesLocalizerFalseDoorTest, AWallHoldsNoMoreFalseDoorsThanTheModelsMost) {
  const map::Map map = CorridorWithALongWall();
  const map::MatchIndex index(map);
  ErrorModel per_inch = ErrorModel::Paper();
  per_inch.wall_false_door_per_in = 0.0015;
  ErrorModel one = per_inch, two = per_inch;
  one.wall_false_doors_max = 1;
  two.wall_false_doors_max = 2;
  const Confusion cf = Resolve(one, index);
  EXPECT_TRUE(cf.AnotherFalseDoor(0));
  EXPECT_FALSE(cf.AnotherFalseDoor(1));
  EXPECT_TRUE(Resolve(per_inch, index).AnotherFalseDoor(7));

  const double any = TruthAfterTwoFalseDoors(index, per_inch);
  const double at_most_one = TruthAfterTwoFalseDoors(index, one);
  const double at_most_two = TruthAfterTwoFalseDoors(index, two);
  EXPECT_LT(at_most_one, 0.5) << "a second false door in one wall was explained";
  EXPECT_GT(at_most_two, 0.9);
  EXPECT_NEAR(at_most_two, any, 0.05);
}

TEST(BayesLocalizerFalseDoorTest, ARatePerInchKeepsThePosteriorNormalised) {
  const map::Map map = CorridorWithALongWall();
  const map::MatchIndex index(map);
  ErrorModel per_inch = ErrorModel::Paper();
  per_inch.wall_false_door_per_in = 0.0015;
  BayesLocalizer b = MakeLocalizer(index, per_inch);
  for (const map::SensedEdge& e :
       {Wall(100, kNaN, true), Door(DoorClass::k36), Wall(150), Door(DoorClass::k30), Wall(170),
        Door(DoorClass::k32), Wall(218), Door(DoorClass::k40)}) {
    b.Add(e);
    double sum = 0.0;
    for (int g = 0; g < index.EdgeCount(); ++g) {
      sum += b.PoseProbability(g, +1) + b.PoseProbability(g, -1);
    }
    EXPECT_NEAR(sum, 1.0, 1e-9);
  }
}

// The 90 in wall is sensed whole; the 36 in door after it cannot be a false door inside
// that wall (90 + 36 > 90). With the fit, the wall's place keeps only what an unexplained
// edge leaves there, however often such walls and doors repeat; without it (the study's
// model) the false door is taken after a first part anywhere in the wall.
BayesLocalizer WallThenDoor(const map::MatchIndex& index, bool false_door_fit) {
  BayesLocalizer b = MakeLocalizer(index, ErrorModel::Paper(), 0.99, 0, false_door_fit);
  b.Add(Wall(150, kNaN, true));
  b.Add(Door(DoorClass::k40));
  b.Add(Wall(90));
  b.Add(Door(DoorClass::k36));
  return b;
}

TEST_F(BayesLocalizerTest, AWallSensedWholeLeavesNoRoomForAFalseDoorInIt) {
  const BayesLocalizer b = WallThenDoor(index_, true);
  EXPECT_EQ(b.best().edge, 9);
  EXPECT_LT(b.PoseProbability(8, +1), 2.0 * b.model().settings.outlier)
      << "belief left on a false door inside the 90 in wall";
}

TEST_F(BayesLocalizerTest, WithoutTheFitAFalseDoorIsTakenInsideAWallSensedWhole) {
  const BayesLocalizer b = WallThenDoor(index_, false);
  EXPECT_EQ(b.best().edge, 9);
  EXPECT_GT(b.PoseProbability(8, +1), 2.0 * b.model().settings.outlier);
}

TEST_F(BayesLocalizerTest, ExplainsAMissedDoorAsOneLongWall) {
  BayesLocalizer b = Make(ErrorModel::Paper());
  b.Add(Wall(150, kNaN, true));
  b.Add(Door(DoorClass::k40));
  b.Add(Wall(201));  // 90 + missed 36 + 75
  b.Add(Door(DoorClass::k40));
  b.Add(Wall(150, 90.0));
  EXPECT_EQ(b.best().edge, 12);
  EXPECT_EQ(b.best().dir, +1);
  EXPECT_GT(b.best().probability, 0.9);
}

// A stretch with a 36 in door between two walls and one with a single wall as long as the
// two and the door (210 in), each between a 36 in door and a 40 in door:
//   0 W120 1 D36 2 W90 3 D36 4 W75 5 D40 6 W150 | 7 W120 8 D36 9 W210 10 D40 11 W150 |
// (nodes 0 and 7, marked |, are 90 deg corners; the rest 180 deg).
map::Map CorridorWithAWallAsLongAsADoorBetweenTwo() {
  using map::Edge;
  return testing::ClosedCorridor(
      {Edge::Wall(120), Edge::Door(DoorClass::k36), Edge::Wall(90), Edge::Door(DoorClass::k36),
       Edge::Wall(75), Edge::Door(DoorClass::k40), Edge::Wall(150), Edge::Wall(120),
       Edge::Door(DoorClass::k36), Edge::Wall(210), Edge::Door(DoorClass::k40), Edge::Wall(150)},
      {0, 7});
}

// The belief in the stretch with the missed door (edge 5) over the one with the long wall
// (edge 10) after a 36 in door, a 210 in wall and a 40 in door: the first has the door missed
// and its wall read 9 in long (201 in true), as the live pipeline reads such walls.
double MissedDoorOverLongWall(const ErrorModel& em) {
  const map::Map map = CorridorWithAWallAsLongAsADoorBetweenTwo();
  const map::MatchIndex index(map);
  BayesLocalizer b = MakeLocalizer(index, em, 0.99, 0);
  for (const map::SensedEdge& e :
       {Wall(100, kNaN, true), Door(DoorClass::k36), Wall(210), Door(DoorClass::k40)}) {
    b.Add(e);
  }
  return b.PoseProbability(5, +1) / b.PoseProbability(10, +1);
}

TEST(BayesLocalizerWallTest, AWallOverAMissedDoorIsWeighedAsTheModelReadsSuchWalls) {
  ErrorModel em = ErrorModel::Paper();
  const double without = MissedDoorOverLongWall(em);
  em.wall_over_missed_door = ErrorModel::WallOverMissedDoor{3.5, 3.1};
  em.Validate();
  const double with = MissedDoorOverLongWall(em);
  // Without the key the 9 in are 3 sigma off the 201 in: the missed door's 0.06 times
  // exp(-4.4); with it 1.3 sigma off a wider normal: 0.06 times 0.45 x 3.05 / 4.35.
  EXPECT_LT(without, 0.005);
  EXPECT_GT(with / without, 10.0);
  EXPECT_LT(with, 0.06);
  // The shift alone, without the spread, moves the wall's mean to 204.5 in.
  em.wall_over_missed_door = ErrorModel::WallOverMissedDoor{3.5, 0.0};
  EXPECT_GT(MissedDoorOverLongWall(em), without);
}

// Along the test corridor: inside the 120 in wall, the 36 in door 1 seen; the 60 in wall 2,
// the 36 in door 3 missed and a false 30 in door right at the start of the 60 in wall 4, so
// the sensed wall (96 in true) reads an inch short. The belief in wall 4 forwards (its first
// part, then the false door in it) after those edges.
double AFalseDoorJustPastAMissedDoor(bool first_part_in_noise) {
  const map::Map map = testing::CorridorMap();
  const map::MatchIndex index(map);
  BayesModel m;
  m.confusion = Resolve(ErrorModel::Paper(), index);
  m.noise = SensingNoise{};
  m.settings.threshold = 0.99;
  m.settings.first_part_in_noise = first_part_in_noise;
  BayesLocalizer b(index, m);
  for (const map::SensedEdge& e :
       {Wall(100, kNaN, true), Door(DoorClass::k36), Wall(95), Door(DoorClass::k30)}) {
    b.Add(e);
  }
  return b.PoseProbability(4, +1);
}

TEST(BayesLocalizerWallTest, AFirstPartReadShorterThanNothingIsStillAFirstPart) {
  // Without the slack the 95 in wall cannot end in wall 4's first part (that needs more
  // than 96 in): the truth is left to the outlier. With it the truth's own path holds.
  EXPECT_LT(AFalseDoorJustPastAMissedDoor(false), 0.01);
  EXPECT_GT(AFalseDoorJustPastAMissedDoor(true), 0.05);
}

// The first sensed wall is seen from the start point on; where the pipeline missed a door
// between the start and the wall, the sensed wall began in that door or in the wall before
// it (AddPrior).
class BayesLocalizerFirstWallTest : public ::testing::Test {
 protected:
  BayesLocalizer Make(const ErrorModel& em) {
    BayesModel m;
    m.confusion = Resolve(em, index_);
    m.noise = SensingNoise{};
    m.settings.threshold = 0.99;
    m.settings.false_door_fit = true;
    m.settings.w2_over_missed_doors = true;
    return BayesLocalizer(index_, m);
  }
  map::Map map_ = testing::CorridorMap();
  map::MatchIndex index_{map_};
};

TEST_F(BayesLocalizerFirstWallTest, AStartInTheWallIsNotAlsoCountedInTheDoorsBehindIt) {
  // Without false doors, a 50 in partial wall inside the 120 in wall 0 started in wall 0
  // whichever way the robot travels: travelling back, door 1 and wall 2 lie behind it, but a
  // start there would have seen more than 120 in. Both directions weigh alike.
  ErrorModel em = ErrorModel::Paper();
  em.wall_false_door = 0.0;
  em.Validate();
  BayesLocalizer b = Make(em);
  b.Add(Wall(50, kNaN, true));
  EXPECT_NEAR(b.PoseProbability(0, -1) / b.PoseProbability(0, +1), 1.0, 1e-9);
  // 140 in is longer than wall 0: only a start inside door 1, missed, explains it
  // travelling back; forward nothing is behind wall 0 but a corner.
  BayesLocalizer longer = Make(em);
  longer.Add(Wall(140, kNaN, true));
  EXPECT_GT(longer.PoseProbability(0, -1), 100.0 * longer.PoseProbability(0, +1));
}

TEST_F(BayesLocalizerFirstWallTest, APartialWallMayRunOverAMissedDoorIntoAFirstPart) {
  // Forward: 30 in of the 60 in wall 2 seen, the 36 in door 3 missed, 10 in of wall 4 and a
  // false 36 in door in it; then the 14 in rest of wall 4 and the 32 in door 5. The first
  // wall (76 in) is longer than wall 4: only the run from behind puts the false door there.
  // On this small floor the sequence fits other places better (the 60 in walls are alike),
  // but the truth's own path must hold its share, not the outlier's (about 1e-9 before).
  BayesLocalizer b = Make(ErrorModel::Paper());
  b.Add(Wall(76, kNaN, true));
  b.Add(Door(DoorClass::k36));
  const double at_false_door = b.PoseProbability(4, +1);
  b.Add(Wall(14));
  b.Add(Door(DoorClass::k32));
  EXPECT_GT(at_false_door, 1e-4);
  EXPECT_GT(b.PoseProbability(5, +1), 0.01);
}

TEST_F(BayesLocalizerFirstWallTest, TheRestOfAWallSeenInPartMayRunOverAMissedDoor) {
  // Forward inside the 120 in wall 0: 40 in seen to a false 36 in door, then its 34 in rest,
  // the 36 in door 1 missed and the 60 in wall 2 as one 130 in wall, and the 36 in door 3.
  // Where the rest began is known only from below (the start was not seen): it is at most
  // 44 in. Without the run-on the truth held 0.002 after the 130 in wall.
  BayesLocalizer b = Make(ErrorModel::Paper());
  b.Add(Wall(40, kNaN, true));
  b.Add(Door(DoorClass::k36));
  b.Add(Wall(130));
  const double at_wall = b.PoseProbability(2, +1);
  b.Add(Door(DoorClass::k36));
  EXPECT_GT(at_wall, 0.05);
  EXPECT_GT(b.PoseProbability(3, +1), 0.1);
}

TEST_F(BayesLocalizerTest, ExplainsAMissizedDoor) {
  BayesLocalizer b = Make(ErrorModel::Paper());
  b.Add(Wall(60, kNaN, true));        // inside the 90 in wall
  b.Add(Door(DoorClass::k40, 38.9));  // the 36 in door 9, classed 40
  b.Add(Wall(75));
  b.Add(Door(DoorClass::k40));
  b.Add(Wall(150, 90.0));
  EXPECT_EQ(b.best().edge, 12);
  EXPECT_EQ(b.best().dir, +1);
}

// The test corridor and a wing off it: a corridor outline whose end is open (an opening
// between two 270 deg corners, map::IsOpenEnd), walked with the wall on the right:
//   13 open end 88 | 14 W100 15 D30/30 16 W80 | 17 W88 (far end) | 18 W120 19 D30 20 W60
map::Map CorridorWithWing() {
  using map::Edge;
  const map::Map corridor = testing::CorridorMap();
  map::Ring wing;
  wing.id = "wing";
  Edge open_end;
  open_end.type = map::EdgeType::kOpening;
  open_end.metric_in = 88;
  wing.edges = {open_end, Edge::Wall(100), Edge::Door(DoorClass::k30_30), Edge::Wall(80),
                Edge::Wall(88), Edge::Wall(120), Edge::Door(DoorClass::k30), Edge::Wall(60)};
  for (const double angle : {270.0, 270.0, 180.0, 180.0, 90.0, 90.0, 180.0, 180.0}) {
    map::Node n;
    n.angle_deg = angle;
    wing.nodes.push_back(n);
  }
  return map::Map(corridor.info(), {corridor.ring(0), wing});
}

class BayesLocalizerOpenEndTest : public ::testing::Test {
 protected:
  // The posterior on the corridor's two 40 in doors (edges 7 and 11), both directions.
  static double OnTheForties(const BayesLocalizer& b) {
    double p = 0.0;
    for (const int g : {7, 11}) p += b.PoseProbability(g, +1) + b.PoseProbability(g, -1);
    return p;
  }
  map::Map map_ = CorridorWithWing();
  map::MatchIndex index_{map_};
};

TEST_F(BayesLocalizerOpenEndTest, BeliefThatLeavesThroughAnOpenEndStartsAgainFromThePrior) {
  const map::MatchIndex& index = index_;
  ASSERT_TRUE(index.open_end(13));
  ASSERT_FALSE(index.open_end(0));
  BayesLocalizer b = MakeLocalizer(index, ErrorModel::Paper());
  // Down the wing's far side toward its open end: sure of the place.
  b.Add(Wall(70, kNaN, true));
  b.Add(Door(DoorClass::k30));
  b.Add(Wall(60));
  ASSERT_EQ(b.best().edge, 20);
  ASSERT_EQ(b.best().dir, +1);
  // Out through the open end into the corridor, where the next thing seen is a 40 in door:
  // the wing has nothing more to say, and the belief lies on the corridor's 40 in doors
  // (edges 7 and 11), not on the open end taken for a wall.
  b.Add(Door(DoorClass::k40));
  double wing = 0.0;
  for (int g = 0; g < index.EdgeCount(); ++g) {
    if (index.RingOf(g) == 1) wing += b.PoseProbability(g, +1) + b.PoseProbability(g, -1);
  }
  EXPECT_LT(wing, 0.25);
  EXPECT_GT(OnTheForties(b), 0.5);
  // The corridor then tells which 40 in door it was.
  b.Add(Wall(90));
  b.Add(Door(DoorClass::k36));
  b.Add(Wall(75));
  EXPECT_EQ(b.best().edge, 10);
  EXPECT_EQ(b.best().dir, +1);
  EXPECT_EQ(b.status(), RecoveryStatus::kLocalized);
}

TEST_F(BayesLocalizerOpenEndTest, TheLastWallBeforeAnOpenEndMayRunOnOutThroughIt) {
  BayesLocalizer b = MakeLocalizer(index_, ErrorModel::Paper());
  b.Add(Wall(70, kNaN, true));
  b.Add(Door(DoorClass::k30));
  // The 60 in wall before the open end, measured on to the door seen outside: 100 in more.
  b.Add(Wall(160));
  b.Add(Door(DoorClass::k40));
  EXPECT_GT(OnTheForties(b), 0.5);
  b.Add(Wall(90));
  b.Add(Door(DoorClass::k36));
  b.Add(Wall(75));
  EXPECT_EQ(b.best().edge, 10);
  EXPECT_EQ(b.best().dir, +1);
}

// Two places that read alike when a door is missed: a row of two 36 in doors 40 in apart
// (edges 1-3), whose second door missed leaves W40 + D36 + W200 = 276 in of wall, and a 36
// in door alone before a 276 in wall (edges 7-8):
//   | 0 W120 1 D36 2 W40 3 D36 4 W200 5 D32 | 6 W120 7 D36 8 W276 9 D32 | 10 W500
// (nodes 0, 6 and 10, marked |, are 90 deg corners; the rest 180 deg).
map::Map CorridorWithARowOfDoors() {
  using map::Edge;
  return testing::ClosedCorridor(
      {Edge::Wall(120), Edge::Door(DoorClass::k36), Edge::Wall(40), Edge::Door(DoorClass::k36),
       Edge::Wall(200), Edge::Door(DoorClass::k32), Edge::Wall(120), Edge::Door(DoorClass::k36),
       Edge::Wall(276), Edge::Door(DoorClass::k32), Edge::Wall(500)},
      {0, 6, 10});
}

// On CorridorWithARowOfDoors, after the walk from a corner that reads the row's first door
// and a 276 in wall: the belief in the row (its second door missed, ending on door 5) over
// the belief in the door alone (read as it is, ending on door 9).
double RowOverDoorAlone(const map::MatchIndex& index, const ErrorModel& em) {
  BayesLocalizer b = MakeLocalizer(index, em);
  for (const map::SensedEdge& e :
       {Wall(120), Door(DoorClass::k36), Wall(276), Door(DoorClass::k32)}) {
    b.Add(e);
  }
  return b.PoseProbability(5, +1) / b.PoseProbability(9, +1);
}

TEST(BayesLocalizerRowTest, ADoorMissedInARowWeighsAsTheModelsRowsMissThem) {
  const map::Map map = CorridorWithARowOfDoors();
  const map::MatchIndex index(map);
  ASSERT_TRUE(index.in_row(1) && index.in_row(2) && index.in_row(3));
  ASSERT_FALSE(index.in_row(5) || index.in_row(7) || index.in_row(8));
  const auto ratio = [&](const ErrorModel& em) { return RowOverDoorAlone(index, em); };
  ErrorModel alone = ErrorModel::Paper();
  alone.by_class[DoorClass::k36] = {0.90, 0.04, 0.06};
  ErrorModel rows = alone;
  rows.in_row = ErrorModel::InRow{};
  rows.in_row->by_class[DoorClass::k36] = {0.38, 0.02, 0.60};
  rows.Validate();
  // Without the rows' rates: the row's first door read right and its second missed against
  // the lone door read right, 0.06; with them, 0.38 x 0.60 / 0.90. The rest of both walks
  // (the walls, the 32 in door alone) weighs alike.
  const double before = ratio(alone), after = ratio(rows);
  EXPECT_NEAR(after / before, (0.38 * 0.60 / 0.90) / 0.06, 0.05 * (0.38 * 0.60 / 0.90) / 0.06);
  EXPECT_LT(before, 0.1);
  EXPECT_GT(after, 0.2);
}

TEST(BayesLocalizerRowTest, ADoorOfARowAfterASeenDoorIsMissedAtTheRateAfterASeenOne) {
  const map::Map map = CorridorWithARowOfDoors();
  const map::MatchIndex index(map);
  const auto ratio = [&](const ErrorModel& em) { return RowOverDoorAlone(index, em); };
  ErrorModel rows = ErrorModel::Paper();
  rows.by_class[DoorClass::k36] = {0.90, 0.04, 0.06};
  rows.in_row = ErrorModel::InRow{};
  rows.in_row->by_class[DoorClass::k36] = {0.38, 0.02, 0.60};
  ErrorModel linked = rows;
  linked.in_row->door_missed_after_seen[DoorClass::k36] = 0.15;
  linked.in_row->door_missed_after_missed[DoorClass::k36] = 0.90;
  linked.Validate();
  // The row's second door was missed after its first was seen: 0.15, not the row's 0.60.
  // The first door, after a 120 in wall, is read at the row's rates either way.
  EXPECT_NEAR(ratio(linked) / ratio(rows), 0.15 / 0.60, 0.01);
}

// A row of double doors between 46 in panels, as on the Engineering Building's wings, and a
// stretch whose doors are where the row's reading below puts them:
//   0 W120 1 D36 2 W46 3 D36/36 4 W46 5 D30/30 6 W46 7 D36 8 W200 9 D40 10 W150 |
//   11 W120 12 D36 13 W121 14 D40 15 W66 16 D40 17 W8 18 D36 19 W200 20 D40 21 W150 |
// (nodes 0 and 11, marked |, are 90 deg corners; the rest 180 deg).
map::Map CorridorWithARowOfDoubleDoors() {
  using map::Edge;
  return testing::ClosedCorridor({Edge::Wall(120),
                                  Edge::Door(DoorClass::k36),
                                  Edge::Wall(46),
                                  Edge::Door(DoorClass::k36_36),
                                  Edge::Wall(46),
                                  Edge::Door(DoorClass::k30_30),
                                  Edge::Wall(46),
                                  Edge::Door(DoorClass::k36),
                                  Edge::Wall(200),
                                  Edge::Door(DoorClass::k40),
                                  Edge::Wall(150),
                                  Edge::Wall(120),
                                  Edge::Door(DoorClass::k36),
                                  Edge::Wall(121),
                                  Edge::Door(DoorClass::k40),
                                  Edge::Wall(66),
                                  Edge::Door(DoorClass::k40),
                                  Edge::Wall(8),
                                  Edge::Door(DoorClass::k36),
                                  Edge::Wall(200),
                                  Edge::Door(DoorClass::k40),
                                  Edge::Wall(150)},
                                 {0, 11});
}

// The belief in door 9 forwards of the row of double doors after the walk from its first
// corner: 120 in of wall, door 1 read, then one sensed wall over doors 3, 5 and 7, all missed
// (edges 2 to 8 end to end), and door 9 read. The live outlier share; the row's doors missed
// 60 % of the time (the live pipeline misses double doors in a row more often still: 78-85 %
// on the Engineering Building, docs/whereami.md).
double TruthOverThreeMissedDoors(int max_missed_doors) {
  const map::Map map = CorridorWithARowOfDoubleDoors();
  const map::MatchIndex index(map);
  ErrorModel em = ErrorModel::Paper();
  for (DoorClass k : {DoorClass::k36, DoorClass::k36_36, DoorClass::k30_30}) {
    em.by_class[k] = {0.40, 0.0, 0.60};
  }
  em.Validate();
  BayesModel m;
  m.confusion = Resolve(em, index);
  m.noise = SensingNoise{};
  m.settings.threshold = 0.99;
  m.settings.outlier = 0.01;
  m.settings.max_missed_doors = max_missed_doors;
  BayesLocalizer b(index, m);
  double wall_in = 0.0;
  for (int g = 2; g <= 8; ++g) wall_in += index.metric(g);
  for (const map::SensedEdge& e :
       {Wall(120), Door(DoorClass::k36), Wall(wall_in), Door(DoorClass::k40)}) {
    b.Add(e);
  }
  return b.PoseProbability(9, +1);
}

TEST(BayesLocalizerRowTest, AWallOverThreeMissedDoorsNeedsTheFilterToAllowThree) {
  // Allowing two, no path of the model reaches door 9 through the one long wall: the truth
  // keeps only what the outlier spreads. Allowing three or more, its own path holds it.
  const double two = TruthOverThreeMissedDoors(2);
  const double three = TruthOverThreeMissedDoors(3);
  const double four = TruthOverThreeMissedDoors(4);
  EXPECT_LT(two, 0.01) << "three " << three;
  EXPECT_GT(three, 0.5) << "two " << two;
  EXPECT_NEAR(four, three, 1e-9);
}

// The paper's rates, with the double doors of a row missed and its panels read as doors as
// often as the live pipeline does (configs/error_model_rows.yaml).
ErrorModel RowOfDoubleDoorsModel() {
  ErrorModel em = ErrorModel::Paper();
  em.in_row = ErrorModel::InRow{};
  em.in_row->wall_false_door = 0.44;
  em.in_row->by_class[DoorClass::k36_36] = {0.05, 0.25, 0.70};
  em.in_row->by_class[DoorClass::k30_30] = {0.05, 0.35, 0.60};
  em.false_door_classes = {{DoorClass::k40, 0.7}, {DoorClass::k36, 0.3}};
  em.Validate();
  return em;
}

// The belief in the truth (the 40 in door, edge 9, walked forward) over the belief in the
// stretch of real doors (edge 20), after the row is read with its double doors missed and the
// panels beyond them read as 40 in doors: the wall after the first false door is its panel's
// last 3 in, the 30/30 missed and the next panel's first 3 in.
double TruthOverTheRealDoors(const ErrorModel& em, bool w2_over_missed) {
  const map::Map map = CorridorWithARowOfDoubleDoors();
  const map::MatchIndex index(map);
  BayesModel m;
  m.confusion = Resolve(em, index);
  m.noise = SensingNoise{};
  m.settings.threshold = 0.99;
  m.settings.w2_over_missed_doors = w2_over_missed;
  BayesLocalizer b(index, m);
  for (const map::SensedEdge& e :
       {Wall(100, kNaN, true), Door(DoorClass::k36), Wall(121), Door(DoorClass::k40), Wall(66),
        Door(DoorClass::k40), Wall(3), Door(DoorClass::k36), Wall(200), Door(DoorClass::k40)}) {
    b.Add(e);
  }
  return b.PoseProbability(9, +1) / b.PoseProbability(20, +1);
}

TEST(BayesLocalizerRowTest, TheRestOfAPanelReadAsADoorRunsOnOverTheMissedDoorBeyondIt) {
  const ErrorModel em = RowOfDoubleDoorsModel();
  const double off = TruthOverTheRealDoors(em, false);
  const double on = TruthOverTheRealDoors(em, true);
  // Off, "wall:66" after the first false door is the outlier's and the real doors win; on, it
  // is the panel's rest, the missed 30/30 and the next panel's first part, and the truth wins
  // over a stretch that needs its 8 in wall read as 3 in.
  EXPECT_LT(off, 0.1);
  EXPECT_GT(on, 1.0);
  EXPECT_GT(on / off, 100.0);
}

TEST(BayesLocalizerRowTest, APanelAfterAMissedDoorHoldsAFalseDoorAtItsOwnRate) {
  ErrorModel flat = RowOfDoubleDoorsModel();
  ErrorModel by_before = flat;
  by_before.in_row->wall_false_door_after_missed = 0.70;
  by_before.in_row->wall_false_door_after_seen = 0.06;
  by_before.Validate();
  const map::Map map = CorridorWithARowOfDoubleDoors();
  const map::MatchIndex index(map);
  const Confusion c = Resolve(by_before, index);
  EXPECT_DOUBLE_EQ(c.FalseDoorIn(46, true, Confusion::Before::kDoorMissed), 0.70);
  EXPECT_DOUBLE_EQ(c.FalseDoorIn(46, true, Confusion::Before::kDoorSeen), 0.06);
  EXPECT_DOUBLE_EQ(c.FalseDoorIn(46, true), 0.44);
  EXPECT_DOUBLE_EQ(c.FalseDoorIn(200, false, Confusion::Before::kDoorMissed), flat.wall_false_door);
  // The truth's reading: the panel after the 36 in door seen held no false door (0.94 against
  // 0.56), the two after the missed double doors held one each (0.70 against 0.44, twice):
  // 4.2 on its main path. The real doors' 8 in wall, a wall of a row after a door seen, holds
  // none (0.94 against 0.56 too), and the truth's other paths (the first panel read with a
  // false door, say) weigh otherwise: the truth still gains more than twice.
  const double gain = TruthOverTheRealDoors(by_before, true) / TruthOverTheRealDoors(flat, true);
  EXPECT_GT(gain, 2.0);
  EXPECT_LT(gain, (0.94 / 0.56) * (0.70 / 0.44) * (0.70 / 0.44));
}

// The odds of the truth after the row of double doors is read with its 36/36 missed and
// the 30/30 after it seen: door 1 read, one wall over edges 2-4, and door 5 read (the truth,
// walked forward).
double TruthOddsWithTheSecondDoubleDoorRead(double missed_after_missed) {
  const map::Map map = CorridorWithARowOfDoubleDoors();
  const map::MatchIndex index(map);
  ErrorModel em = RowOfDoubleDoorsModel();
  em.in_row->door_missed_after_seen = {{DoorClass::k36_36, 0.70}, {DoorClass::k30_30, 0.60}};
  em.in_row->door_missed_after_missed = {{DoorClass::k36_36, 0.70},
                                         {DoorClass::k30_30, missed_after_missed}};
  em.Validate();
  BayesLocalizer b = MakeLocalizer(index, em);
  const double wall_in = index.metric(2) + index.metric(3) + index.metric(4);
  for (const map::SensedEdge& e :
       {Wall(120), Door(DoorClass::k36), Wall(wall_in), Door(DoorClass::k30_30)}) {
    b.Add(e);
  }
  const double p = b.PoseProbability(5, +1);
  return p / (1.0 - p);
}

TEST(BayesLocalizerRowTest, ADoorOfARowReadAfterAMissedDoorWeighsAtTheRatesAfterAMissedOne) {
  // The 30/30 after the missed 36/36 read right 70 % of the time against 10 %: its read
  // rates scale by (1 - 0.3) / 0.4 and (1 - 0.9) / 0.4, seven times apart, on the truth's
  // path; the filter must carry what the door before the panel was through the sensed wall.
  const double likely = TruthOddsWithTheSecondDoubleDoorRead(0.30);
  const double unlikely = TruthOddsWithTheSecondDoubleDoorRead(0.90);
  EXPECT_GT(likely / unlikely, 4.0) << likely << " " << unlikely;
  EXPECT_LT(likely / unlikely, 7.5) << likely << " " << unlikely;
}

// A corridor with a 36/36 double door (edge 1), and a single 36 in door (edge 6) where a
// read of the double door's second leaf, with the first in the wall before it, fits exactly:
//   0 W120 1 D36/36 2 W80 3 D40 4 W150 | 5 W156 6 D36 7 W80 8 D40 9 W200 |
// (nodes 0 and 5, marked |, are 90 deg corners; the rest 180 deg).
map::Map CorridorWithDoubleDoor() {
  using map::Edge;
  return testing::ClosedCorridor(
      {Edge::Wall(120), Edge::Door(DoorClass::k36_36), Edge::Wall(80), Edge::Door(DoorClass::k40),
       Edge::Wall(150), Edge::Wall(156), Edge::Door(DoorClass::k36), Edge::Wall(80),
       Edge::Door(DoorClass::k40), Edge::Wall(200)},
      {0, 5});
}

// The paper's rates, with a double door read as one leaf as often as the live pipeline does
// (configs/error_model_live.yaml), or never (`leaf` false: no leaf reads at all).
ErrorModel WithLeafReads(bool leaf) {
  ErrorModel em = ErrorModel::Paper();
  if (!leaf) return em;
  em.by_class[DoorClass::k36_36] = {0.52, 0.47, 0.01};
  em.missized_to[DoorClass::k36_36] = {{DoorClass::k36, 0.6}, {DoorClass::k40, 0.3},
                                       {DoorClass::k30, 0.1}};
  em.leaf_split = 0.6;
  em.leaf_sliver = 0.15;
  em.leaf_wall_before = 0.15;
  em.leaf_wall_after = 0.05;
  em.Validate();
  return em;
}

class BayesLocalizerLeafTest : public ::testing::Test {
 protected:
  // The belief on the 40 in door after the double door (edge 3), walked forward, after
  // the sensed edges (which end there).
  double OnTheDoorAfter(bool leaf, const std::vector<map::SensedEdge>& sensed) {
    BayesLocalizer b = MakeLocalizer(index_, WithLeafReads(leaf));
    for (const map::SensedEdge& e : sensed) b.Add(e);
    return b.PoseProbability(3, +1);
  }
  map::Map map_ = CorridorWithDoubleDoor();
  map::MatchIndex index_{map_};
};

TEST_F(BayesLocalizerLeafTest, AFirstLeafReadIntoTheWallBeforeTheDoorLeavesTheSingleDoorUnsure) {
  // Wall 0 (120 in) read with the first leaf (36 in): 156 in; the second leaf as a 36. The
  // single door 6 fits that exactly; the double door must keep enough belief that the
  // filter is not sure of door 6, and win once the next wall tells them apart.
  std::vector<map::SensedEdge> sensed = {Wall(100, kNaN, true), Wall(156, 90.0),
                                         Door(DoorClass::k36), Wall(80), Door(DoorClass::k40)};
  BayesLocalizer with = MakeLocalizer(index_, WithLeafReads(true));
  BayesLocalizer without = MakeLocalizer(index_, WithLeafReads(false));
  for (const map::SensedEdge& e : sensed) {
    with.Add(e);
    without.Add(e);
  }
  EXPECT_EQ(without.status(), RecoveryStatus::kLocalized);  // sure of door 8: wrong
  EXPECT_EQ(without.best().edge, 8);
  EXPECT_NE(with.status(), RecoveryStatus::kLocalized);
  EXPECT_GT(with.PoseProbability(3, +1), 0.01);
  with.Add(Wall(150));
  EXPECT_EQ(with.best().edge, 4);
  EXPECT_GT(with.best().probability, 0.8);
}

TEST_F(BayesLocalizerLeafTest, BothLeavesReadAsTwoDoorsAreOneDoubleDoor) {
  const std::vector<map::SensedEdge> sensed = {Wall(150, 90.0, true), Wall(120, 90.0),
                                               Door(DoorClass::k36), Door(DoorClass::k36),
                                               Wall(80), Door(DoorClass::k40)};
  EXPECT_GT(OnTheDoorAfter(true, sensed), 0.99);
  EXPECT_LT(OnTheDoorAfter(false, sensed), 0.5);
}

TEST_F(BayesLocalizerLeafTest, BothLeavesWithASliverOfWallBetweenThemAreOneDoubleDoor) {
  const std::vector<map::SensedEdge> sensed = {Wall(150, 90.0, true), Wall(120, 90.0),
                                               Door(DoorClass::k36), Wall(5),
                                               Door(DoorClass::k36), Wall(80),
                                               Door(DoorClass::k40)};
  EXPECT_GT(OnTheDoorAfter(true, sensed), 0.8);
  EXPECT_LT(OnTheDoorAfter(false, sensed), 0.5);
}

TEST_F(BayesLocalizerLeafTest, ASecondLeafReadIntoTheWallAfterTheDoorIsExplained) {
  // One leaf as a 36, the other in wall 2: 80 + 36 = 116 in.
  const std::vector<map::SensedEdge> sensed = {Wall(150, 90.0, true), Wall(120, 90.0),
                                               Door(DoorClass::k36), Wall(116),
                                               Door(DoorClass::k40)};
  BayesLocalizer with = MakeLocalizer(index_, WithLeafReads(true));
  BayesLocalizer without = MakeLocalizer(index_, WithLeafReads(false));
  for (const map::SensedEdge& e : sensed) {
    with.Add(e);
    without.Add(e);
  }
  EXPECT_EQ(with.best().edge, 3);
  EXPECT_GT(with.PoseProbability(3, +1), 10.0 * without.PoseProbability(3, +1));
}

TEST_F(BayesLocalizerLeafTest, TheLeafPhasesKeepThePosteriorNormalised) {
  BayesLocalizer b = MakeLocalizer(index_, WithLeafReads(true));
  for (const map::SensedEdge& e : {Wall(150, 90.0, true), Wall(156, 90.0), Door(DoorClass::k36)}) {
    b.Add(e);
  }
  double sum = 0.0;
  for (int g = 0; g < index_.EdgeCount(); ++g) {
    sum += b.PoseProbability(g, +1) + b.PoseProbability(g, -1);
  }
  EXPECT_NEAR(sum, 1.0, 1e-9);
}

// Sure of edge 10 forward, then carried to the other end of the corridor: the edges sensed
// there (edges 1-5) contradict the held place. With a kidnap share per edge the belief
// drains to the new place; without one it has nowhere to go but the old place's neighbours.
TEST_F(BayesLocalizerTest, AKidnapShareLetsTheBeliefMoveToWhereTheRobotWasCarried) {
  const auto run = [this](double kidnap) {
    BayesModel m;
    m.confusion = Resolve(ErrorModel::Paper(), index_);
    m.settings.threshold = 0.99;
    m.settings.kidnap_per_edge = kidnap;
    BayesLocalizer b(index_, m);
    for (const map::SensedEdge& e : {Wall(150, kNaN, true), Door(DoorClass::k40), Wall(90),
                                     Door(DoorClass::k36), Wall(75)}) {
      b.Add(e);
    }
    EXPECT_EQ(b.best().edge, 10);
    for (const map::SensedEdge& e : {Door(DoorClass::k36), Wall(60), Door(DoorClass::k36),
                                     Wall(60), Door(DoorClass::k32)}) {
      b.Add(e);
    }
    return b;
  };
  const BayesLocalizer carried = run(0.01);
  EXPECT_EQ(carried.best().edge, 5);
  EXPECT_EQ(carried.best().dir, +1);
  EXPECT_GT(carried.best().probability, 0.9);
  const BayesLocalizer held = run(0.0);
  EXPECT_LT(held.PoseProbability(5, +1), carried.PoseProbability(5, +1));
}

// "D36 W60 D36" (edges 1-3) reads the same either way along the ring: travelled forward it
// ends at edge 3, backward at edge 1. Knowing the direction of travel settles it.
TEST_F(BayesLocalizerTest, AKnownTravelDirectionSettlesAStretchThatReadsTheSameEitherWay) {
  const auto run = [this](int ring_dir) {
    BayesLocalizer b = Make(ErrorModel::Paper());
    b.SetTravelDirection(ring_dir);
    for (const map::SensedEdge& e : {Door(DoorClass::k36), Wall(60), Door(DoorClass::k36)}) {
      b.Add(e);
    }
    return b;
  };
  const BayesLocalizer either = run(0);
  EXPECT_NEAR(either.PoseProbability(3, +1), either.PoseProbability(1, -1), 0.05);
  EXPECT_LT(either.best().probability, 0.6);
  for (const int dir : {+1, -1}) {
    const BayesLocalizer known = run(dir);
    EXPECT_EQ(known.best().dir, dir);
    EXPECT_EQ(known.best().edge, dir > 0 ? 3 : 1);
    EXPECT_GT(known.best().probability, 0.9);
    double other = 0.0, total = 0.0;
    for (int g = 0; g < index_.EdgeCount(); ++g) {
      other += known.PoseProbability(g, -dir);
      total += known.PoseProbability(g, +1) + known.PoseProbability(g, -1);
    }
    EXPECT_EQ(other, 0.0);
    EXPECT_NEAR(total, 1.0, 1e-9);
  }
}

// A reversal turns the belief held; the prior a kidnap share draws from after it goes to the
// new direction alone.
TEST_F(BayesLocalizerTest, AfterAReversalThePriorGoesToTheNewDirection) {
  BayesModel m;
  m.confusion = Resolve(ErrorModel::Paper(), index_);
  m.settings.threshold = 0.99;
  m.settings.kidnap_per_edge = 0.01;
  BayesLocalizer b(index_, m);
  b.SetTravelDirection(+1);
  for (const map::SensedEdge& e :
       {Wall(150, kNaN, true), Door(DoorClass::k40), Wall(90), Door(DoorClass::k36), Wall(75)}) {
    b.Add(e);
  }
  ASSERT_EQ(b.best().edge, 10);
  b.Reverse();
  b.SetTravelDirection(-1);
  b.Add(Wall(30, kNaN, true));
  b.Add(Wall(75));
  b.Add(Door(DoorClass::k36));
  double forward = 0.0;
  for (int g = 0; g < index_.EdgeCount(); ++g) forward += b.PoseProbability(g, +1);
  EXPECT_EQ(forward, 0.0);
  EXPECT_EQ(b.best().edge, 9);
  EXPECT_EQ(b.best().dir, -1);
}

TEST_F(BayesLocalizerTest, InvalidEdgesAreRejected) {
  BayesLocalizer b = Make(ErrorModel::Paper());
  map::SensedEdge e = Door(DoorClass::k36);
  e.metric_in = -1.0;
  EXPECT_EQ(b.Add(e), RecoveryStatus::kEmpty);
  EXPECT_EQ(b.rejected(), 1u);
  EXPECT_EQ(b.edges(), 0);
}

TEST_F(BayesLocalizerTest, ResetForgetsTheBelief) {
  BayesLocalizer b = Make(ErrorModel::Paper());
  b.Add(Door(DoorClass::k32));
  b.Reset();
  EXPECT_EQ(b.status(), RecoveryStatus::kEmpty);
  EXPECT_EQ(b.edges(), 0);
}

// The corridor with a poster on door 1 and a vision panel on door 3: both are 36 in doors
// followed by a 60 in wall, so class and wall length cannot tell them apart.
class BayesLocalizerMarkTest : public ::testing::Test {
 protected:
  static map::Map MarkedCorridor() {
    const map::Map plain = testing::CorridorMap();
    map::Ring ring = plain.ring(0);
    ring.edges[1].pattern = "poster";
    ring.edges[3].pattern = "old_window";
    return map::Map(plain.info(), {ring});
  }
  static ErrorModel WithMarks() {
    ErrorModel em = ErrorModel::Paper();
    em.mark_read[map::DoorMark::kPlain] = {0.2, 0.7, 0.08, 0.02};
    em.mark_read[map::DoorMark::kWindow] = {0.2, 0.1, 0.6, 0.1};
    em.mark_read[map::DoorMark::kPoster] = {0.2, 0.05, 0.1, 0.65};
    em.false_door_marks = ErrorModel::MarkRow{0.3, 0.6, 0.08, 0.02};
    return em;
  }
  // The belief in door 1's place over door 3's after "door36 wall:60", the door read `mark`.
  double Ratio(const ErrorModel& em, map::DoorMark mark) const {
    BayesLocalizer b = MakeLocalizer(index_, em);
    map::SensedEdge door = Door(DoorClass::k36);
    door.mark = mark;
    b.Add(door);
    b.Add(Wall(60));
    return b.PoseProbability(2, +1) / b.PoseProbability(4, +1);
  }
  map::Map map_ = MarkedCorridor();
  map::MatchIndex index_{map_};
};

TEST_F(BayesLocalizerMarkTest, APosterReadTellsApartDoorsTheClassCannot) {
  EXPECT_NEAR(Ratio(ErrorModel::Paper(), map::DoorMark::kPoster), 1.0, 1e-6);  // marks unused
  // P(poster | poster) / P(poster | window) = 0.65 / 0.1.
  EXPECT_NEAR(Ratio(WithMarks(), map::DoorMark::kPoster), 6.5, 0.05);
  EXPECT_NEAR(Ratio(WithMarks(), map::DoorMark::kWindow), 0.1 / 0.6, 0.005);
  // Unread: both marks leave a door unread as often, so it says nothing.
  EXPECT_NEAR(Ratio(WithMarks(), map::DoorMark::kUnknown), 1.0, 0.01);
}

TEST_F(BayesLocalizerMarkTest, TheMarksKeepThePosteriorNormalised) {
  BayesLocalizer b = MakeLocalizer(index_, WithMarks());
  map::SensedEdge door = Door(DoorClass::k36);
  door.mark = map::DoorMark::kWindow;
  for (const map::SensedEdge& e : {Wall(100, kNaN, true), door, Wall(60), door, Wall(200)}) {
    b.Add(e);
    double sum = 0.0;
    for (const PoseBelief& p : b.Top(1000)) sum += p.probability;
    EXPECT_NEAR(sum, 1.0, 1e-6);
  }
}

}  // namespace
}  // namespace stickrep::recovery
