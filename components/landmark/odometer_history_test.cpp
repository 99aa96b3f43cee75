#include "landmark/odometer_history.h"

#include <gtest/gtest.h>

namespace stickrep::landmark {
namespace {

TEST(OdometerHistoryTest, InterpolatesBetweenReadings) {
  OdometerHistory h;
  h.Add(1'000'000'000, 10.0);
  h.Add(1'100'000'000, 13.0);
  EXPECT_DOUBLE_EQ(*h.At(1'050'000'000, 0), 11.5);
}

TEST(OdometerHistoryTest, ClampsWithinTheExtrapolationLimitAndRefusesBeyond) {
  OdometerHistory h;
  h.Add(1'000'000'000, 10.0);
  EXPECT_DOUBLE_EQ(*h.At(1'040'000'000, 50'000'000), 10.0);
  EXPECT_FALSE(h.At(1'200'000'000, 50'000'000).has_value());
}

TEST(OdometerHistoryTest, PastTheNewestReadingTheLastSpeedIsCarriedOn) {
  OdometerHistory h;
  h.Add(1'000'000'000, 10.0);
  h.Add(1'200'000'000, 16.24);
  EXPECT_DOUBLE_EQ(*h.At(1'400'000'000, 300'000'000), 22.48);
}

TEST(OdometerHistoryTest, OutOfOrderReadingIsRefused) {
  OdometerHistory h;
  h.Add(2, 1.0);
  EXPECT_FALSE(h.Add(1, 0.0));
}

TEST(OdometerHistoryTest, KeepsOnlyTheNewestReadings) {
  OdometerHistory h(2);
  h.Add(1, 1.0);
  h.Add(2, 2.0);
  h.Add(3, 3.0);
  EXPECT_FALSE(h.At(1, 0).has_value());
  EXPECT_DOUBLE_EQ(*h.At(2, 0), 2.0);
}

TEST(OdometerHistoryTest, EmptyHistoryHasNoReading) {
  OdometerHistory h;
  EXPECT_FALSE(h.At(5, 1'000'000'000).has_value());
}

}  // namespace
}  // namespace stickrep::landmark
