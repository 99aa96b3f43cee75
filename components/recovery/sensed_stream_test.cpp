#include "recovery/sensed_stream.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "recovery/test_support.h"
#include "stickrep/map_io.h"

namespace stickrep::recovery {
namespace {

class SensedStreamTest : public ::testing::Test {
 protected:
  map::Map map_ = testing::CorridorMap();
  map::MatchIndex index_{map_};
  SensingNoise quiet_ = [] {
    SensingNoise n = SensingNoise::None();
    n.class_region_in = DefaultClassRegions();
    return n;
  }();
  map::MatchTolerance exact_{0.0, 0.0, 10.0};
};

TEST_F(SensedStreamTest, WithoutErrorEveryEdgeIsTheMapEdge) {
  const Confusion clean = Resolve(ErrorModel::None(), index_);
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    SensedStream s(index_, clean, quiet_, exact_, seed);
    int g = s.start().edge;
    for (int i = 0; i < 20; ++i) {
      const StreamEdge* e = s.At(i);
      ASSERT_NE(e, nullptr);
      EXPECT_TRUE(e->faithful);
      EXPECT_EQ(e->truth, g);
      EXPECT_EQ(e->sensed.code, index_.code(g));
      if (i > 0 && !map::IsDoorCode(e->sensed.code)) {
        EXPECT_NEAR(e->sensed.metric_in, index_.metric(g), 1e-9);
      }
      g = index_.Step(g, s.dir());
    }
  }
}

TEST_F(SensedStreamTest, SameSeedSameRun) {
  const Confusion c = Resolve(ErrorModel::Paper(), index_);
  const SensingNoise noise = SensingNoise{[] {
    SensingNoise n;
    n.class_region_in = DefaultClassRegions();
    return n;
  }()};
  SensedStream a(index_, c, noise, exact_, 99), b(index_, c, noise, exact_, 99);
  for (int i = 0; i < 30; ++i) {
    EXPECT_EQ(a.At(i)->sensed.code, b.At(i)->sensed.code);
    EXPECT_EQ(a.At(i)->sensed.metric_in, b.At(i)->sensed.metric_in);
  }
}

TEST_F(SensedStreamTest, AFalseDoorSplitsTheWallItSitsIn) {
  ErrorModel em = ErrorModel::None();
  em.wall_false_door = 1.0;
  const Confusion c = Resolve(em, index_);
  SensedStream s(index_, c, quiet_, exact_, 3);
  // Find a wall split in three: W1 + ribbon + W2 = the map wall.
  int found = 0;
  for (int i = 1; i + 2 < 40; ++i) {
    const StreamEdge* w1 = s.At(i);
    const StreamEdge* d = s.At(i + 1);
    const StreamEdge* w2 = s.At(i + 2);
    if (w1->sensed.code != map::kWallCode || !map::IsDoorCode(d->sensed.code) ||
        w2->sensed.code != map::kWallCode || w1->truth != w2->truth || d->faithful) {
      continue;
    }
    EXPECT_TRUE(w1->with_next);
    EXPECT_NEAR(w1->sensed.metric_in + d->sensed.metric_in + w2->sensed.metric_in,
                index_.metric(w1->truth), 1e-6);
    ++found;
  }
  EXPECT_GT(found, 3);
}

// The study keeps the pointer to a wall while it asks for the door that ends it; with the
// edges in a vector that reallocated, that pointer was left dangling (ASan: a
// heap-use-after-free in this file's AFalseDoorSplitsTheWallItSitsIn).
TEST_F(SensedStreamTest, AnEdgeStaysWhereItIsAsLaterEdgesAreGenerated) {
  const Confusion c = Resolve(ErrorModel::None(), index_);
  SensedStream s(index_, c, quiet_, exact_, 7);
  const StreamEdge* first = s.At(0);
  ASSERT_NE(first, nullptr);
  const StreamEdge copy = *first;
  ASSERT_NE(s.At(500), nullptr);
  EXPECT_EQ(s.At(0), first);
  EXPECT_EQ(first->truth, copy.truth);
  EXPECT_EQ(first->sensed.metric_in, copy.sensed.metric_in);
}

TEST_F(SensedStreamTest, MissedDoorsJoinTheWallsAroundThem) {
  ErrorModel em = ErrorModel::None();
  em.door_correct = 0.0;
  em.door_missed = 1.0;
  const Confusion c = Resolve(em, index_);
  SensedStream s(index_, c, quiet_, exact_, 5);
  // No door is ever sensed; between the two corners the walls and doors are one wall:
  // the corner-to-corner stretch W120 D36 W60 D36 W60 D32 W200 D40 W90 D36 W75 D40 = 825 in,
  // and the 150 in wall between the two corners.
  for (int i = 0; i < 10; ++i) {
    const StreamEdge* e = s.At(i);
    EXPECT_EQ(e->sensed.code, map::kWallCode);
    if (i > 0) {
      EXPECT_TRUE(std::abs(e->sensed.metric_in - 150.0) < 1e-6 ||
                  std::abs(e->sensed.metric_in - 825.0) < 1e-6)
          << e->sensed.metric_in;
    }
  }
}

TEST_F(SensedStreamTest, AWallOverMissedDoorsIsReadLongerPerMissedDoor) {
  ErrorModel em = ErrorModel::None();
  em.door_correct = 0.0;
  em.door_missed = 1.0;
  em.wall_over_missed_door = ErrorModel::WallOverMissedDoor{2.0, 0.0};
  const Confusion shift = Resolve(em, index_);
  SensedStream shifted(index_, shift, quiet_, exact_, 5);
  em.wall_over_missed_door->sigma_in = 3.0;
  const Confusion shift_and_spread = Resolve(em, index_);
  SensedStream spread(index_, shift_and_spread, quiet_, exact_, 5);
  // The 825 in stretch runs over its six doors: 12 in longer; the 150 in wall over none.
  int long_walls = 0;
  for (int i = 1; i < 10; ++i) {
    const double m = shifted.At(i)->sensed.metric_in;
    EXPECT_TRUE(std::abs(m - 150.0) < 1e-6 || std::abs(m - 837.0) < 1e-6) << m;
    const double n = spread.At(i)->sensed.metric_in;
    if (std::abs(m - 150.0) < 1e-6) {
      EXPECT_NEAR(n, 150.0, 1e-6);
    } else {
      EXPECT_GT(std::abs(n - 837.0), 1e-6) << "no spread drawn";
      EXPECT_LT(std::abs(n - 837.0), 5.0 * std::sqrt(6.0) * 3.0);
      ++long_walls;
    }
  }
  EXPECT_GT(long_walls, 0);
}

// A row of four 36 in doors 40 in apart (the walls between them are in the row).
map::Map RowMap() {
  using map::DoorClass;
  using map::Edge;
  return testing::ClosedCorridor(
      {Edge::Wall(120), Edge::Door(DoorClass::k36), Edge::Wall(40), Edge::Door(DoorClass::k36),
       Edge::Wall(40), Edge::Door(DoorClass::k36), Edge::Wall(40), Edge::Door(DoorClass::k36),
       Edge::Wall(200)},
      {0, 8});
}

TEST_F(SensedStreamTest, ARowWallHoldsAFalseDoorByTheDoorBeforeIt) {
  const map::Map row_map = RowMap();
  const map::MatchIndex index(row_map);
  ErrorModel em = ErrorModel::None();
  em.door_correct = 0.5;
  em.door_missed = 0.5;
  em.false_door_classes = {{map::DoorClass::k30, 1.0}};
  em.in_row = ErrorModel::InRow{};
  em.in_row->wall_false_door = 0.5;
  em.in_row->wall_false_door_after_missed = 1.0;
  em.in_row->wall_false_door_after_seen = 0.0;
  const Confusion c = Resolve(em, index);
  int after_missed = 0, after_seen = 0;
  for (std::uint64_t seed = 0; seed < 40; ++seed) {
    SensedStream s(index, c, quiet_, exact_, seed);
    for (int i = 2; i < 40; ++i) {
      const StreamEdge* e = s.At(i);
      const int w = e->truth;
      if (!index.in_row(w) || !(index.code(w) == map::kWallCode)) continue;
      const bool false_door = map::IsDoorCode(e->sensed.code);
      if (false_door) {
        // W1 before it; the true door before the wall was missed, so no sensed door stands
        // for it just before W1.
        const StreamEdge* before = s.At(i - 2);
        EXPECT_FALSE(map::IsDoorCode(before->sensed.code) &&
                     before->truth == index.Step(w, -s.dir()))
            << "seed " << seed << " edge " << i;
        ++after_missed;
      } else if (map::IsDoorCode(s.At(i - 1)->sensed.code) &&
                 s.At(i - 1)->truth == index.Step(w, -s.dir())) {
        // After a door seen the row wall is read whole.
        EXPECT_TRUE(e->faithful) << "seed " << seed << " edge " << i;
        ++after_seen;
      }
    }
  }
  EXPECT_GT(after_missed, 20);
  EXPECT_GT(after_seen, 20);
}

TEST_F(SensedStreamTest, ARowsDoorIsMissedByTheDoorBeforeIt) {
  const map::Map row_map = RowMap();
  const map::MatchIndex index(row_map);
  ErrorModel em = ErrorModel::None();
  em.in_row = ErrorModel::InRow{};
  em.in_row->by_class[map::DoorClass::k36] = {0.5, 0.0, 0.5};
  // Each door after a short wall does what the door before it did; the row's first door
  // (after the 120 in wall, or the 200 in one going back) is missed half the time.
  em.in_row->door_missed_after_missed[map::DoorClass::k36] = 1.0;
  em.in_row->door_missed_after_seen[map::DoorClass::k36] = 0.0;
  em.Validate();
  const Confusion c = Resolve(em, index);
  std::map<int, int> passes;  // doors sensed in one pass of the row -> passes
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    SensedStream s(index, c, quiet_, exact_, seed);
    int doors = 0;
    bool whole = false;  // a pass counted from its start
    for (int i = 0; i < 40; ++i) {
      const StreamEdge* e = s.At(i);
      if (e->truth == 8) {  // the 200 in wall between the corners: one per pass
        if (whole) ++passes[doors];
        whole = true;
        doors = 0;
      } else if (map::IsDoorCode(e->sensed.code)) {
        ++doors;
      }
    }
  }
  // All four doors seen or none: without the rates by the door before, 1 to 3 as well.
  for (const auto& [doors, n] : passes) EXPECT_TRUE(doors == 0 || doors == 4) << doors << " x" << n;
  EXPECT_GT(passes[0], 5);
  EXPECT_GT(passes[4], 5);
}

TEST_F(SensedStreamTest, ThePerInchModelPutsUpToItsMostFalseDoorsInOneWall) {
  ErrorModel em = ErrorModel::None();
  em.wall_false_door = 0.0;
  em.false_door_classes = {{map::DoorClass::k30, 1.0}};
  em.wall_false_door_per_in = 0.1;  // a wall of 75 in or more almost surely holds one
  for (const int most : {1, 2}) {
    em.wall_false_doors_max = most;
    const Confusion c = Resolve(em, index_);
    int max_seen = 0;
    for (std::uint64_t seed = 0; seed < 20; ++seed) {
      SensedStream s(index_, c, quiet_, exact_, seed);
      // False doors in a row of sensed edges with the same true wall: one visit of it.
      int in_wall = 0, wall = -1;
      for (int i = 1; i < 60; ++i) {
        const StreamEdge* e = s.At(i);
        if (e->truth != wall) in_wall = 0;
        wall = e->truth;
        if (index_.code(wall) == map::kWallCode && map::IsDoorCode(e->sensed.code)) ++in_wall;
        max_seen = std::max(max_seen, in_wall);
      }
    }
    EXPECT_EQ(max_seen, most) << "wall_false_doors_max " << most;
  }
}

TEST(RunSeeds, DifferForEveryTrialAndRun) {
  EXPECT_NE(RunSeed(1, 0, 1), RunSeed(1, 1, 0));
  EXPECT_NE(RunSeed(1, 0, 0), RunSeed(2, 0, 0));
  EXPECT_EQ(RunSeed(7, 3, 4), RunSeed(7, 3, 4));
}

TEST_F(SensedStreamTest, DoorsCarryAMarkDrawnFromTheirOwnMarksReads) {
  // Every true door is plain on this map; plain leaves are read plain or unknown, false
  // doors always as posters.
  ErrorModel em = ErrorModel::None();
  em.wall_false_door = 0.3;
  em.mark_read[map::DoorMark::kPlain] = {0.5, 0.5, 0.0, 0.0};
  em.false_door_marks = ErrorModel::MarkRow{0.0, 0.0, 0.0, 1.0};
  const Confusion cf = Resolve(em, index_);
  int doors = 0, unknown = 0, false_doors = 0;
  for (std::uint64_t seed = 0; seed < 40; ++seed) {
    SensedStream s(index_, cf, quiet_, exact_, seed);
    for (int i = 0; i < 20; ++i) {
      const StreamEdge* e = s.At(i);
      ASSERT_NE(e, nullptr);
      if (!map::IsDoorCode(e->sensed.code)) {
        EXPECT_EQ(e->sensed.mark, map::DoorMark::kUnknown);
        continue;
      }
      if (map::IsDoorCode(index_.code(e->truth)) && e->faithful) {
        ++doors;
        EXPECT_NE(e->sensed.mark, map::DoorMark::kWindow);
        EXPECT_NE(e->sensed.mark, map::DoorMark::kPoster);
        unknown += e->sensed.mark == map::DoorMark::kUnknown;
      } else if (!map::IsDoorCode(index_.code(e->truth))) {
        ++false_doors;
        EXPECT_EQ(e->sensed.mark, map::DoorMark::kPoster);
      }
    }
  }
  ASSERT_GT(doors, 100);
  EXPECT_GT(false_doors, 10);
  EXPECT_NEAR(static_cast<double>(unknown) / doors, 0.5, 0.12);
  // Without marks in the model no door is read.
  const Confusion paper = Resolve(ErrorModel::Paper(), index_);  // the stream keeps a reference
  SensedStream plain(index_, paper, quiet_, exact_, 7);
  for (int i = 0; i < 20; ++i) EXPECT_EQ(plain.At(i)->sensed.mark, map::DoorMark::kUnknown);
}

TEST_F(SensedStreamTest, AMisSizedDoorsMarkIsDrawnFromTheMisSizedReads) {
  // Plain leaves read with their class are read plain; mis-sized, as posters.
  ErrorModel em = ErrorModel::None();
  em.door_correct = 0.5;
  em.door_missized = 0.5;
  em.mark_read[map::DoorMark::kPlain] = {0.0, 1.0, 0.0, 0.0};
  em.mark_read_missized[map::DoorMark::kPlain] = {0.0, 0.0, 0.0, 1.0};
  const Confusion cf = Resolve(em, index_);
  int right = 0, missized = 0;
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    SensedStream s(index_, cf, quiet_, exact_, seed);
    for (int i = 0; i < 20; ++i) {
      const StreamEdge* e = s.At(i);
      if (!map::IsDoorCode(e->sensed.code)) continue;
      const bool class_right = e->sensed.code == index_.code(e->truth);
      EXPECT_EQ(e->sensed.mark, class_right ? map::DoorMark::kPlain : map::DoorMark::kPoster);
      ++(class_right ? right : missized);
    }
  }
  EXPECT_GT(right, 30);
  EXPECT_GT(missized, 30);
}

// Double doors between flat walls: W120 D36/36 W100 D36 W80 D36/36 W150 (a corner at node 0).
class SensedLeafTest : public SensedStreamTest {
 protected:
  map::Map leaf_map_ = testing::ClosedCorridor(
      {map::Edge::Wall(120), map::Edge::Door(map::DoorClass::k36_36), map::Edge::Wall(100),
       map::Edge::Door(map::DoorClass::k36), map::Edge::Wall(80),
       map::Edge::Door(map::DoorClass::k36_36), map::Edge::Wall(150)},
      {0});
  map::MatchIndex leaf_index_{leaf_map_};
  // Every double door read as one 36 in leaf (36 in short), the rest of its width as `em`'s
  // leaf reads go; single doors read right.
  Confusion LeafModel(double split, double sliver, double before, double after) const {
    ErrorModel em = ErrorModel::None();
    em.by_class[map::DoorClass::k36_36] = {0.0, 1.0, 0.0};
    em.missized_to[map::DoorClass::k36_36] = {{map::DoorClass::k36, 1.0}};
    em.leaf_split = split;
    em.leaf_sliver = sliver;
    em.leaf_wall_before = before;
    em.leaf_wall_after = after;
    return Resolve(em, leaf_index_);
  }
  // The sensed edges of 20 runs from the third on, each with the one before and after.
  template <typename F>
  void ForEachLeaf(const Confusion& c, F check) const {
    for (std::uint64_t seed = 0; seed < 20; ++seed) {
      SensedStream s(leaf_index_, c, quiet_, exact_, seed);
      for (int i = 2; i < 30; ++i) {
        const StreamEdge* e = s.At(i);
        if (map::IsDoorCode(e->sensed.code) &&
            leaf_index_.code(e->truth) == map::DoorCode(map::DoorClass::k36_36)) {
          check(*s.At(i - 1), *e, *s.At(i + 1), s.dir());
        }
      }
    }
  }
};

TEST_F(SensedLeafTest, TheOtherLeafComesAsASecondDoorAfterASliverOrNot) {
  int seconds = 0, slivers = 0;
  ForEachLeaf(LeafModel(1.0, 0.5, 0.0, 0.0),
              [&](const StreamEdge& before, const StreamEdge& e, const StreamEdge& after, int) {
                EXPECT_EQ(e.sensed.code, map::DoorCode(map::DoorClass::k36));
                if (before.truth == e.truth)
                  return;  // the second leaf, or the first after a sliver
                if (map::IsDoorCode(after.sensed.code)) {
                  EXPECT_EQ(after.truth, e.truth);
                  ++seconds;
                } else {
                  EXPECT_EQ(after.truth, e.truth);  // the sliver of the same door
                  EXPECT_LE(after.sensed.metric_in, 36.0 + 1e-6);
                  ++slivers;
                }
              });
  EXPECT_GT(seconds, 10);
  EXPECT_GT(slivers, 10);
}

TEST_F(SensedLeafTest, TheRestOfTheDoorGoesToTheWallBeforeOrAfter) {
  int longer_before = 0;
  ForEachLeaf(LeafModel(0.0, 0.0, 1.0, 0.0),
              [&](const StreamEdge& before, const StreamEdge&, const StreamEdge&, int) {
                ASSERT_EQ(before.sensed.code, map::kWallCode);
                EXPECT_NEAR(before.sensed.metric_in, leaf_index_.metric(before.truth) + 36.0, 1e-6);
                ++longer_before;
              });
  int longer_after = 0;
  ForEachLeaf(LeafModel(0.0, 0.0, 0.0, 1.0),
              [&](const StreamEdge&, const StreamEdge& e, const StreamEdge& after, int) {
                ASSERT_EQ(after.sensed.code, map::kWallCode);
                EXPECT_NE(after.truth, e.truth);
                EXPECT_NEAR(after.sensed.metric_in, leaf_index_.metric(after.truth) + 36.0, 1e-6);
                ++longer_after;
              });
  EXPECT_GT(longer_before, 10);
  EXPECT_GT(longer_after, 10);
  // Neither: the walls keep their lengths.
  ForEachLeaf(LeafModel(0.0, 0.0, 0.0, 0.0),
              [&](const StreamEdge& before, const StreamEdge&, const StreamEdge& after, int) {
                EXPECT_NEAR(before.sensed.metric_in, leaf_index_.metric(before.truth), 1e-6);
                EXPECT_NEAR(after.sensed.metric_in, leaf_index_.metric(after.truth), 1e-6);
              });
}

TEST(DrawStartTest, StartsOnlyBesideTheRingsGivenInProportionToTheirLength) {
  const map::Map map =
      map::LoadMap(std::string(STICKREP_SOURCE_DIR) + "/maps/engineering_building_3f.yaml");
  const map::MatchIndex index(map);
  ASSERT_GE(index.RingCount(), 3);
  const std::vector<int> rings = {0, 2};
  double length[2] = {0, 0};
  for (int g = 0; g < index.EdgeCount(); ++g) {
    if (index.RingOf(g) == 0) length[0] += index.metric(g);
    if (index.RingOf(g) == 2) length[1] += index.metric(g);
  }
  std::mt19937_64 rng(7);
  int on[2] = {0, 0};
  const int draws = 4000;
  for (int i = 0; i < draws; ++i) {
    const RunStart s = DrawStart(index, rng, rings);
    const int r = index.RingOf(s.edge);
    ASSERT_TRUE(r == 0 || r == 2) << "start on ring " << r;
    ASSERT_GE(s.offset_in, 0.0);
    ASSERT_LE(s.offset_in, index.metric(s.edge));
    ++on[r == 0 ? 0 : 1];
  }
  // Binomial: 4000 draws put the share within 0.03 of the length share (over 3.8 sigma).
  const double expected = length[0] / (length[0] + length[1]);
  EXPECT_NEAR(static_cast<double>(on[0]) / draws, expected, 0.03);
}

TEST(DrawStartTest, EveryRingNamedDrawsWhatNoChoiceDraws) {
  const map::Map map =
      map::LoadMap(std::string(STICKREP_SOURCE_DIR) + "/maps/engineering_building_3f.yaml");
  const map::MatchIndex index(map);
  std::vector<int> every(index.RingCount());
  std::iota(every.begin(), every.end(), 0);
  std::mt19937_64 a(3), b(3);
  for (int i = 0; i < 200; ++i) {
    const RunStart x = DrawStart(index, a);
    const RunStart y = DrawStart(index, b, every);
    ASSERT_EQ(x.edge, y.edge);
    ASSERT_EQ(x.dir, y.dir);
    ASSERT_EQ(x.offset_in, y.offset_in);
  }
}

TEST(DrawStartTest, ARingWithNoEdgeToStartBesideIsRefused) {
  const map::Map map = testing::CorridorMap();
  const map::MatchIndex index(map);
  std::mt19937_64 rng(1);
  EXPECT_THROW(DrawStart(index, rng, {index.RingCount()}), std::invalid_argument);
}

}  // namespace
}  // namespace stickrep::recovery
