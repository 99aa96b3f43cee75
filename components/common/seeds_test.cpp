#include "common/seeds.h"

#include <gtest/gtest.h>

namespace stickrep {
namespace {

TEST(SeedsTest, SplitMix64GivesTheReferenceSequence) {
  // The first two outputs of SplitMix64 from state 0 (the reference implementation's).
  EXPECT_EQ(SplitMix64(0), 0xe220a8397b1dcdafull);
  EXPECT_EQ(StreamSeed(0, 0), 0xe220a8397b1dcdafull);
  EXPECT_EQ(StreamSeed(0, 1), 0x6e789e6aa1b965f4ull);
}

TEST(SeedsTest, AStreamSeedIsAFunctionOfSeedAndIndexOnly) {
  EXPECT_EQ(StreamSeed(7, 3), StreamSeed(7, 3));
  EXPECT_NE(StreamSeed(7, 3), StreamSeed(7, 4));
  EXPECT_NE(StreamSeed(7, 3), StreamSeed(8, 3));
  static_assert(StreamSeed(7, 3) == SplitMix64(7 + 3 * kSplitMixGamma));
}

}  // namespace
}  // namespace stickrep
