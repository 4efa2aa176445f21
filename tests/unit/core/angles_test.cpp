#include "skyfuse/core/angles.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace skyfuse {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(WrapAngle, MapsBothEndsOfTheCutToPlusPi) {
  EXPECT_DOUBLE_EQ(wrap_angle(kPi), kPi);
  EXPECT_DOUBLE_EQ(wrap_angle(-kPi), kPi);
  EXPECT_DOUBLE_EQ(wrap_angle(3.0 * kPi), kPi);
  EXPECT_DOUBLE_EQ(wrap_angle(-3.0 * kPi), kPi);
}

TEST(WrapAngle, StaysInsideHalfOpenInterval) {
  for (double a = -20.0; a <= 20.0; a += 0.001) {
    const double w = wrap_angle(a);
    ASSERT_GT(w, -kPi) << "angle " << a;
    ASSERT_LE(w, kPi) << "angle " << a;
    // Same direction: the difference is a whole number of turns.
    const double turns = (a - w) / (2.0 * kPi);
    ASSERT_NEAR(turns, std::round(turns), 1e-9) << "angle " << a;
  }
}

TEST(WrapAngle, TakesTheShortWayAcrossTheCut) {
  const double just_below = kPi - 0.01;
  const double just_above = -kPi + 0.01;  // the same bearing region, other side of the cut
  EXPECT_NEAR(wrap_angle(just_above - just_below), 0.02, 1e-12);
  EXPECT_NEAR(wrap_angle(just_below - just_above), -0.02, 1e-12);
}

TEST(WrapAngle, LeavesSmallAnglesUntouched) {
  EXPECT_EQ(wrap_angle(0.0), 0.0);
  EXPECT_EQ(wrap_angle(1.0), 1.0);
  EXPECT_EQ(wrap_angle(-1.0), -1.0);
}

}  // namespace
}  // namespace skyfuse
