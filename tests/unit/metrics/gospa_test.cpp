#include "skyfuse/metrics/gospa.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace skyfuse {
namespace {

const std::vector<Vector3> kTruths = {{0, 0, 0}, {10, 0, 0}, {0, 20, 0}};
const std::vector<Vector3> kEstimates = {{1, 0, 0}, {10, 3, 0}, {0, 32, 0}, {50, 50, 0}};

TEST(Gospa, TheWorkedExampleWithOrderTwo) {
  // (0,0)-(1,0) and (10,0)-(10,3) are assigned; (0,20) is 12 m from its nearest estimate, past
  // the cut-off: one missed target and, with (50,50), two false tracks.
  const Gospa g = gospa(kTruths, kEstimates, {.cutoff_m = 10.0, .order = 2.0});
  EXPECT_DOUBLE_EQ(g.localisation, 10.0);
  EXPECT_DOUBLE_EQ(g.missed, 50.0);
  EXPECT_DOUBLE_EQ(g.false_tracks, 100.0);
  EXPECT_NEAR(g.distance, 12.6491, 5e-5);
  EXPECT_DOUBLE_EQ(g.distance, std::sqrt(160.0));
  EXPECT_EQ(g.assigned, 2U);
  EXPECT_EQ(g.missed_targets, 1U);
  EXPECT_EQ(g.false_estimates, 2U);
}

TEST(Gospa, TheWorkedExampleWithOrderOne) {
  const Gospa g = gospa(kTruths, kEstimates, {.cutoff_m = 10.0, .order = 1.0});
  EXPECT_DOUBLE_EQ(g.localisation, 4.0);
  EXPECT_DOUBLE_EQ(g.missed, 5.0);
  EXPECT_DOUBLE_EQ(g.false_tracks, 10.0);
  EXPECT_DOUBLE_EQ(g.distance, 19.0);
}

TEST(Gospa, TwoTruthsAndNoEstimate) {
  const std::vector<Vector3> truths = {{0, 0, 0}, {100, 0, 0}};
  const Gospa g = gospa(truths, {}, {.cutoff_m = 10.0, .order = 2.0});
  EXPECT_DOUBLE_EQ(g.distance, 10.0);
  EXPECT_EQ(g.missed_targets, 2U);
}

TEST(Gospa, PerfectTracksScoreZero) {
  const Gospa g = gospa(kTruths, kTruths, {.cutoff_m = 10.0, .order = 2.0});
  EXPECT_EQ(g.distance, 0.0);
  EXPECT_EQ(g.assigned, 3U);
}

TEST(Gospa, TheAssignmentIsTheBestOneNotTheGreedyOne) {
  // Greedy would pair truth 0 with estimate 0 (1 m) and leave truth 1 5 m from estimate 1;
  // the best pairs cross: 2^2 + 2^2 = 8 < 1^2 + 5^2.
  const std::vector<Vector3> truths = {{0, 0, 0}, {3, 0, 0}};
  const std::vector<Vector3> estimates = {{1, 0, 0}, {-2, 0, 0}};
  const Gospa g = gospa(truths, estimates, {.cutoff_m = 20.0, .order = 2.0});
  EXPECT_DOUBLE_EQ(g.localisation, 8.0);
}

TEST(Gospa, RefusesAMeaninglessCutOffOrOrder) {
  EXPECT_THROW(gospa(kTruths, kEstimates, {.cutoff_m = 0.0, .order = 2.0}), std::invalid_argument);
  EXPECT_THROW(gospa(kTruths, kEstimates, {.cutoff_m = 10.0, .order = 0.5}), std::invalid_argument);
}

}  // namespace
}  // namespace skyfuse
