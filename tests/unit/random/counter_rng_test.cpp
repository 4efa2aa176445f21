#include "skyfuse/random/counter_rng.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace skyfuse {
namespace {

TEST(CounterRng, SameKeyGivesTheSameSequence) {
  CounterRng a({1, 2, 3, 4, NoiseStream::kMeasurement});
  CounterRng b({1, 2, 3, 4, NoiseStream::kMeasurement});
  for (int i = 0; i < 100; ++i) ASSERT_EQ(a.next_u64(), b.next_u64());
}

TEST(CounterRng, EveryKeyFieldChangesTheSequence) {
  const NoiseKey base{1, 2, 3, 4, NoiseStream::kMeasurement};
  const std::uint64_t first = CounterRng(base).next_u64();
  NoiseKey k = base;
  k.seed = 9;
  EXPECT_NE(CounterRng(k).next_u64(), first);
  k = base;
  k.run = 9;
  EXPECT_NE(CounterRng(k).next_u64(), first);
  k = base;
  k.station = 9;
  EXPECT_NE(CounterRng(k).next_u64(), first);
  k = base;
  k.step = 9;
  EXPECT_NE(CounterRng(k).next_u64(), first);
  k = base;
  k.stream = NoiseStream::kNoiseScale;
  EXPECT_NE(CounterRng(k).next_u64(), first);
}

TEST(CounterRng, NormalsHaveUnitMomentsAcrossKeys) {
  // Draws taken one per key, as the simulation does: moments must hold across keys too.
  constexpr int kDraws = 200000;
  double sum = 0.0;
  double sum_sq = 0.0;
  for (int i = 0; i < kDraws; ++i) {
    CounterRng rng({5, 0, 1, static_cast<std::uint64_t>(i), NoiseStream::kMeasurement});
    const double x = rng.normal();
    sum += x;
    sum_sq += x * x;
  }
  const double mean = sum / kDraws;
  const double variance = sum_sq / kDraws - mean * mean;
  EXPECT_NEAR(mean, 0.0, 5.0 / std::sqrt(kDraws));  // 5 standard errors
  EXPECT_NEAR(variance, 1.0, 5.0 * std::sqrt(2.0 / kDraws));
}

TEST(CounterRng, UniformNeverReturnsZeroOrOne) {
  CounterRng rng({0, 0, 0, 0, NoiseStream::kMeasurement});
  for (int i = 0; i < 100000; ++i) {
    const double u = rng.uniform();
    ASSERT_GT(u, 0.0);
    ASSERT_LT(u, 1.0);
  }
}

}  // namespace
}  // namespace skyfuse
