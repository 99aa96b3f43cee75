#include "sensing/door_classifier.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace stickrep::sensing {
namespace {

using ::testing::DoubleNear;
using ::testing::Optional;

TEST(DoorClassifierTest, Table41BoundariesClassifyAsPrinted) {
  const auto t = Table41Boundaries();
  EXPECT_THAT(ClassifyWidth(t, 29.1), Optional(DoorClass::k32));
  EXPECT_THAT(ClassifyWidth(t, 33.49), Optional(DoorClass::k32));
  EXPECT_THAT(ClassifyWidth(t, 33.5), Optional(DoorClass::k36));
  EXPECT_THAT(ClassifyWidth(t, 42.6), Optional(DoorClass::k40));
  EXPECT_THAT(ClassifyWidth(t, 60.0), Optional(DoorClass::k30_30));
  EXPECT_THAT(ClassifyWidth(t, 76.2), Optional(DoorClass::k36_36));
}

TEST(DoorClassifierTest, WidthsOutsideEveryClassAreRejected) {
  const auto t = DefaultBoundaries();
  EXPECT_EQ(ClassifyWidth(t, 20.0), std::nullopt);
  EXPECT_EQ(ClassifyWidth(t, 50.0), std::nullopt);
  EXPECT_EQ(ClassifyWidth(t, 80.0), std::nullopt);
  EXPECT_EQ(ClassifyWidth(t, std::numeric_limits<double>::quiet_NaN()), std::nullopt);
}

TEST(DoorClassifierTest, DefaultBoundariesAddDoor30BelowDoor32) {
  const auto t = DefaultBoundaries();
  EXPECT_THAT(ClassifyWidth(t, 30.0), Optional(DoorClass::k30));
  EXPECT_THAT(ClassifyWidth(t, 32.0), Optional(DoorClass::k32));
  EXPECT_THAT(ClassifyWidth(t, 36.0), Optional(DoorClass::k36));
}

TEST(BayesBoundariesTest, DefaultDoor30RegionIsTheDerivedOne) {
  const auto derived = DeriveBayesBoundaries(BayesModel{});
  ASSERT_FALSE(derived.empty());
  ASSERT_EQ(derived.front().door_class, DoorClass::k30);
  const auto in_use = DefaultBoundaries();
  EXPECT_THAT(in_use.front().low_in, DoubleNear(derived.front().low_in, 0.05));
  EXPECT_THAT(in_use.front().high_in, DoubleNear(derived.front().high_in, 0.05));
}

TEST(BayesBoundariesTest, EqualPriorsAndSpreadPutTheBoundaryNearTheMidpoint) {
  BayesModel m;
  m.prior_door30 = m.prior_door32 = m.prior_door36 = m.prior_door40 = 100;
  m.sigma_rel = 0.03;
  const auto b = DeriveBayesBoundaries(m);
  // 36|40 with equal priors: just below 38, because the 40 class is 11 % wider (hand
  // solution of the equal-density equation: 37.92 in).
  for (const ClassBoundary& r : b) {
    if (r.door_class == DoorClass::k36) {
      EXPECT_THAT(r.high_in, DoubleNear(37.92, 0.03));
    }
  }
}

TEST(BayesBoundariesTest, FittedSpreadReproducesTable41InteriorBoundaries) {
  BayesModel m;
  m.sigma_rel = FitSigmaToTable41(m);
  m.prior_door30 = 0;  // as Table 4.1
  for (const ClassBoundary& r : DeriveBayesBoundaries(m)) {
    if (r.door_class == DoorClass::k36) {
      EXPECT_THAT(r.low_in, DoubleNear(33.5, 0.5));
      EXPECT_THAT(r.high_in, DoubleNear(38.8, 0.5));
    }
  }
}

}  // namespace
}  // namespace stickrep::sensing
