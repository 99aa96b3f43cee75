#include "stickrep/sequence_matcher.h"

#include <gtest/gtest.h>

#include "stickrep/map_io.h"
#include "stickrep/test_maps.h"

namespace stickrep::map {
namespace {

class SequenceMatcherTest : public ::testing::Test {
 protected:
  SequenceMatcherTest() : map_(ParseMap(testing::kBoxMapYaml, "box.yaml")), index_(map_) {}
  SensedEdge Wall(double metric, double angle = std::numeric_limits<double>::quiet_NaN()) {
    SensedEdge e;
    e.code = kWallCode;
    e.metric_in = metric;
    e.angle_deg = angle;
    return e;
  }
  SensedEdge Door(DoorClass c) {
    SensedEdge e;
    e.code = DoorCode(c);
    return e;
  }
  Map map_;
  MatchIndex index_;
};

TEST_F(SequenceMatcherTest, IndexStoresRingsContiguously) {
  EXPECT_EQ(index_.EdgeCount(), 8);
  EXPECT_EQ(index_.RingOffset(1), 6);
  EXPECT_EQ(index_.Step(5, +1), 0);
  EXPECT_EQ(index_.Step(0, -1), 5);
  EXPECT_EQ(index_.Step(7, +1), -1);
  EXPECT_EQ(index_.EdgesWithCode(kWallCode).size(), 6u);
}

TEST_F(SequenceMatcherTest, FirstEdgeMatchesEveryPlaceInBothDirections) {
  SequenceMatcher m(index_);
  EXPECT_EQ(m.Extend(Wall(100)), 6u);  // three 100 in walls, two directions each
}

TEST_F(SequenceMatcherTest, DoorThenWallLeavesOnePlace) {
  SequenceMatcher m(index_);
  EXPECT_EQ(m.Extend(Door(DoorClass::k36)), 2u);
  EXPECT_EQ(m.Extend(Wall(24, 180)), 1u);
  EXPECT_EQ(m.candidates()[0].start, 1);
  EXPECT_EQ(m.candidates()[0].dir, +1);
  EXPECT_EQ(m.candidates()[0].last, 2);
}

TEST_F(SequenceMatcherTest, MatchesAgainstRingOrder) {
  SequenceMatcher m(index_);
  m.Extend(Wall(24));
  EXPECT_EQ(m.Extend(Door(DoorClass::k36)), 1u);
  EXPECT_EQ(m.candidates()[0].dir, -1);
}

TEST_F(SequenceMatcherTest, WrongAngleRemovesTheCandidate) {
  SequenceMatcher m(index_);
  m.Extend(Door(DoorClass::k36));
  EXPECT_EQ(m.Extend(Wall(24, 90)), 0u);
}

TEST_F(SequenceMatcherTest, ImpossibleSequenceLeavesNothing) {
  SequenceMatcher m(index_);
  m.Extend(Door(DoorClass::k36));
  EXPECT_EQ(m.Extend(Door(DoorClass::k36)), 0u);
}

TEST_F(SequenceMatcherTest, MetricToleranceAdmitsNearbyWalls) {
  SequenceMatcher exact(index_);
  EXPECT_EQ(exact.Extend(Wall(44)), 0u);
  SequenceMatcher relaxed(index_, MatchTolerance{0.1, 0.0, 0.0});
  EXPECT_EQ(relaxed.Extend(Wall(44)), 2u);  // 40 in +- 10 %
}

TEST_F(SequenceMatcherTest, LowerBoundMatchesAnyLongerWall) {
  SequenceMatcher m(index_);
  SensedEdge partial = Wall(30);
  partial.metric_is_lower_bound = true;
  EXPECT_EQ(m.Extend(partial), 2u * 5u);  // 40, 100, 100, 100 in the box, 50 in the strip
}

TEST_F(SequenceMatcherTest, OpenRingEndDropsCandidates) {
  SequenceMatcher m(index_);
  EXPECT_EQ(m.Extend(Door(DoorClass::k32)), 2u);
  EXPECT_EQ(m.Extend(Wall(50, 180)), 1u);  // only backwards: nothing after the door
}

TEST_F(SequenceMatcherTest, ExactSequenceReproducesTheMapEdges) {
  const std::vector<SensedEdge> seq = ExactSequence(index_, 3, +1, 4);
  ASSERT_EQ(seq.size(), 4u);
  EXPECT_EQ(seq[3].metric_in, 40.0);
  SequenceMatcher m(index_);
  EXPECT_EQ(m.MatchAll(seq), 1u);
  EXPECT_EQ(m.candidates()[0].start, 3);
}

}  // namespace
}  // namespace stickrep::map
