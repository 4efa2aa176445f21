#include "run/round_samples.hpp"

#include <gtest/gtest.h>

namespace skyfuse::harness {
namespace {

// 65 ticks, 128 measurements and 65 tracks besides the increments at M = 64.
constexpr long kCommonAt64 = 65 + 128 + 65;

TEST(RoundSamples, TheFlatExchangeCarriesEveryIncrementToEveryOtherStation) {
  EXPECT_EQ(samples_per_round("flat", 64, 8), kCommonAt64 + 64 * 63);
  EXPECT_EQ(samples_per_round("flat", 1, 8), 2 + 2 + 2);
}

TEST(RoundSamples, TheTreeCarriesContributionsSumsAndTotals) {
  // Eight clusters of eight: 56 contributions, 8 * 7 sums, 56 totals (docs/performance.md).
  EXPECT_EQ(samples_per_round("tree", 64, 8), kCommonAt64 + 56 + 56 + 56);
  // A last cluster of two: ceil(10 / 4) = 3 clusters.
  EXPECT_EQ(samples_per_round("tree", 10, 4), (11 + 20 + 11) + 7 + 6 + 7);
  // One cluster holding everyone: contributions and totals, no sums between aggregators.
  EXPECT_EQ(samples_per_round("tree", 8, 8), (9 + 16 + 9) + 7 + 0 + 7);
}

TEST(RoundSamples, TheTreeGrowsLinearlyWhereTheFlatExchangeGrowsQuadratically) {
  // Doubling M at a fixed fanout: the tree's samples about double (the sums between
  // aggregators grow as (M / k)^2 but stay a small share up to M = k^2), the flat exchange's
  // nearly quadruple.
  EXPECT_LT(samples_per_round("tree", 64, 8), 2 * samples_per_round("tree", 32, 8) + 64);
  EXPECT_GT(samples_per_round("flat", 64, 8), 3 * samples_per_round("flat", 32, 8));
}

TEST(RoundSamples, RunsPastOneHostsPortsGoToSimulatedHostsOfSixtyFourProcesses) {
  EXPECT_EQ(hosts_for(64), 0);
  EXPECT_EQ(hosts_for(99), 0);
  EXPECT_EQ(hosts_for(100), 2);  // 101 processes
  EXPECT_EQ(hosts_for(128), 3);  // 129 processes
  EXPECT_EQ(hosts_for(256), 5);  // 257 processes
}

}  // namespace
}  // namespace skyfuse::harness
