#include "recovery/relaxed_matcher.h"

#include <gtest/gtest.h>

#include <random>

#include "recovery/test_support.h"

namespace stickrep::recovery {
namespace {

using map::DoorClass;
using testing::Door;
using testing::Wall;

class RelaxedMatcherTest : public ::testing::Test {
 protected:
  map::Map map_ = testing::CorridorMap();
  map::MatchIndex index_{map_};
  RelaxedMatcher matcher_{index_, map::MatchTolerance{0.0, 0.0, 10.0}};
};

TEST_F(RelaxedMatcherTest, ExactSequenceMatchesOnlyWhereItCameFrom) {
  const auto seq = map::ExactSequence(index_, 5, +1, 4);  // D32 W200 D40 W90
  EXPECT_EQ(matcher_.MatchAll(seq), 1u);
  EXPECT_EQ(matcher_.candidates()[0].start, 5);
  EXPECT_EQ(matcher_.candidates()[0].last, 8);
  EXPECT_EQ(matcher_.candidates()[0].dir, +1);
}

TEST_F(RelaxedMatcherTest, MatchesAgainstRingOrder) {
  const auto seq = map::ExactSequence(index_, 10, -1, 3);  // W75 D36 W90, walking backwards
  ASSERT_EQ(matcher_.MatchAll(seq), 1u);
  EXPECT_EQ(matcher_.candidates()[0].last, 8);
  EXPECT_EQ(matcher_.candidates()[0].dir, -1);
}

TEST_F(RelaxedMatcherTest, ToleranceAdmitsAWallWithinIt) {
  RelaxedMatcher tolerant(index_, map::MatchTolerance{0.05, 0.0, 10.0});
  const std::vector<map::SensedEdge> seq = {Door(DoorClass::k40), Wall(93.0)};
  EXPECT_EQ(matcher_.MatchAll(seq), 0u);
  EXPECT_EQ(tolerant.MatchAll(seq), 1u);
}

TEST_F(RelaxedMatcherTest, ImpossibleSequenceLeavesNoCandidate) {
  const std::vector<map::SensedEdge> seq = {Door(DoorClass::k32), Wall(75.0)};
  EXPECT_EQ(matcher_.MatchAll(seq), 0u);
}

TEST_F(RelaxedMatcherTest, AmbiguousSequenceLeavesSeveralCandidates) {
  // D36 then W60: doors 1 and 3 forwards, door 3 backwards.
  const std::vector<map::SensedEdge> seq = {Door(DoorClass::k36), Wall(60.0)};
  EXPECT_EQ(matcher_.MatchAll(seq), 3u);
}

TEST_F(RelaxedMatcherTest, DoorRelaxationAcceptsANeighbouringClassByWidth) {
  // A 36 in door measured 38.5 in and classed 40, before the 60 in wall: only door 3 or 1.
  const std::vector<map::SensedEdge> seq = {Door(DoorClass::k40, 38.5), Wall(60.0)};
  EXPECT_EQ(matcher_.MatchAll(seq), 0u);
  matcher_.SetRelaxation(0.0, 0.10);
  EXPECT_EQ(matcher_.MatchAll(seq), 3u);
}

TEST_F(RelaxedMatcherTest, DoorRelaxationRejectsAFarClass) {
  matcher_.SetRelaxation(0.0, 0.10);
  const std::vector<map::SensedEdge> seq = {Door(DoorClass::k30_30, 60.0)};
  EXPECT_EQ(matcher_.MatchAll(seq), 0u);
}

TEST_F(RelaxedMatcherTest, WithoutDoorRelaxationItEqualsSequenceMatcher) {
  map::SequenceMatcher plain(index_, map::MatchTolerance{0.0, 0.0, 10.0});
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    const int start = static_cast<int>(rng() % index_.EdgeCount());
    const int dir = rng() % 2 ? 1 : -1;
    auto seq = map::ExactSequence(index_, start, dir, 1 + static_cast<int>(rng() % 5));
    if (rng() % 2) seq.back().metric_in += 7.0;  // sometimes spoil it
    EXPECT_EQ(matcher_.MatchAll(seq), plain.MatchAll(seq));
  }
}

}  // namespace
}  // namespace stickrep::recovery
