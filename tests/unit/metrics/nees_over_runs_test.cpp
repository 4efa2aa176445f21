#include "skyfuse/metrics/nees_over_runs.hpp"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>
#include <vector>

namespace skyfuse {
namespace {

constexpr int kDof = 3;

// `runs` runs of `samples` NEES values each, `scale` times chi-square(kDof); each drawn value is
// held for `held` samples in a row, as a track carries one error over successive rounds.
std::vector<RunNees> simulated_runs(int runs, int samples, int held, double scale,
                                    std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::chi_squared_distribution<double> nees(kDof);
  std::vector<RunNees> out;
  for (int r = 0; r < runs; ++r) {
    double sum = 0.0;
    double value = 0.0;
    for (int i = 0; i < samples; ++i) {
      if (i % held == 0) value = scale * nees(rng);
      sum += value;
    }
    out.push_back({sum / samples, kDof, static_cast<std::size_t>(samples)});
  }
  return out;
}

TEST(NeesOverRuns, IndependentSamplesVaryAsTheChiSquareSays) {
  const auto summary = nees_over_runs(simulated_runs(40, 500, 1, 1.0, 11));
  ASSERT_TRUE(summary.has_value());
  EXPECT_EQ(summary->samples, 40u * 500u);
  EXPECT_EQ(summary->dof, kDof);
  // The variance of 40 runs is known to sqrt(2 / 39) = 23 %: four of those either side.
  EXPECT_GT(summary->variance_over_independent, 0.1);
  EXPECT_LT(summary->variance_over_independent, 1.9);
  EXPECT_TRUE(summary->pooled_band.contains(summary->over_runs.mean));
  EXPECT_TRUE(summary->over_runs.contains(1.0));
}

// A value held for 50 samples makes the runs vary about 50 times as independent samples would:
// the pooled band is then too narrow to judge the filter, the runs' interval is not.
TEST(NeesOverRuns, CorrelatedSamplesWidenTheRunsSpreadNotThePooledBand) {
  const auto summary = nees_over_runs(simulated_runs(40, 500, 50, 1.0, 12));
  ASSERT_TRUE(summary.has_value());
  EXPECT_GT(summary->variance_over_independent, 20.0);
  EXPECT_LT(summary->variance_over_independent, 100.0);
  EXPECT_TRUE(summary->over_runs.contains(1.0));
  const double pooled_width = summary->pooled_band.upper - summary->pooled_band.lower;
  const double runs_width = summary->over_runs.upper - summary->over_runs.lower;
  EXPECT_GT(runs_width, 4.0 * pooled_width);
}

// A filter whose NEES is twice its dof is judged against itself: independent samples of
// 2 chi-square vary as independent samples, and both tests put it above 1.
TEST(NeesOverRuns, AnOverconfidentFilterFailsBothTests) {
  const auto summary = nees_over_runs(simulated_runs(40, 500, 1, 2.0, 13));
  ASSERT_TRUE(summary.has_value());
  EXPECT_NEAR(summary->over_runs.mean, 2.0, 0.05);
  EXPECT_GT(summary->variance_over_independent, 0.1);
  EXPECT_LT(summary->variance_over_independent, 1.9);
  EXPECT_FALSE(summary->over_runs.contains(1.0));
  EXPECT_FALSE(summary->pooled_band.contains(summary->over_runs.mean));
  EXPECT_GT(summary->over_runs.lower, 1.9);
}

TEST(NeesOverRuns, RunsWithoutSamplesAreLeftOutAndDifferentDofsRefused) {
  EXPECT_FALSE(nees_over_runs(std::vector<RunNees>{}).has_value());
  EXPECT_FALSE(nees_over_runs(std::vector<RunNees>{{0.0, 6, 0}}).has_value());
  const auto one = nees_over_runs(std::vector<RunNees>{{0.0, 6, 0}, {6.6, 6, 100}});
  ASSERT_TRUE(one.has_value());
  EXPECT_EQ(one->samples, 100u);
  EXPECT_EQ(one->runs, 1u) << "a run of no samples is not counted among those judged";
  EXPECT_DOUBLE_EQ(one->over_runs.mean, 1.1);
  const std::vector<RunNees> mixed{{6.0, 6, 100}, {3.0, 3, 100}};
  EXPECT_THROW(nees_over_runs(mixed), std::invalid_argument);
}

}  // namespace
}  // namespace skyfuse
