#include "skyfuse/metrics/run_mean_interval.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

namespace skyfuse {
namespace {

// Reference quantiles from standard t tables (e.g. NIST/SEMATECH e-Handbook 1.3.6.7.2).
TEST(StudentT, QuantilesMatchTables) {
  EXPECT_NEAR(student_t_quantile(0.975, 1), 12.7062, 1e-4);
  EXPECT_NEAR(student_t_quantile(0.975, 4), 2.7764, 1e-4);
  EXPECT_NEAR(student_t_quantile(0.975, 7), 2.3646, 1e-4);
  EXPECT_NEAR(student_t_quantile(0.95, 10), 1.8125, 1e-4);
  EXPECT_NEAR(student_t_quantile(0.975, 49), 2.0096, 1e-4);
  EXPECT_NEAR(student_t_quantile(0.025, 49), -2.0096, 1e-4);
  EXPECT_NEAR(student_t_quantile(0.5, 3), 0.0, 1e-12);
}

// One and two degrees of freedom have closed forms: the Cauchy distribution's
// 1/2 + atan(t)/pi and 1/2 + t / (2 sqrt(2 + t^2)).
TEST(StudentT, CdfMatchesTheClosedFormsOfOneAndTwoDegrees) {
  for (double t : {-30.0, -2.5, -0.3, 0.0, 0.7, 4.0, 100.0}) {
    EXPECT_NEAR(student_t_cdf(t, 1), 0.5 + std::atan(t) / std::numbers::pi, 1e-13) << t;
    EXPECT_NEAR(student_t_cdf(t, 2), 0.5 + t / (2.0 * std::sqrt(2.0 + t * t)), 1e-13) << t;
  }
}

TEST(StudentT, CdfInvertsTheQuantile) {
  for (double dof : {1.0, 3.0, 9.0, 49.0, 5000.0}) {
    for (double p : {0.001, 0.025, 0.5, 0.975, 0.999}) {
      EXPECT_NEAR(student_t_cdf(student_t_quantile(p, dof), dof), p, 1e-10)
          << "dof " << dof << " p " << p;
    }
  }
}

TEST(RunMeanInterval, IsTheMeanPlusMinusTTimesTheStandardError) {
  // 1..5: mean 3, s = sqrt(2.5), t(0.975, 4) = 2.776445: half-width 2.776445 sqrt(2.5 / 5).
  const RunMeanInterval interval = run_mean_interval({1.0, 2.0, 3.0, 4.0, 5.0});
  EXPECT_DOUBLE_EQ(interval.mean, 3.0);
  EXPECT_NEAR(interval.standard_deviation, std::sqrt(2.5), 1e-15);
  EXPECT_NEAR(interval.lower, 3.0 - 2.776445 * std::sqrt(0.5), 1e-5);
  EXPECT_NEAR(interval.upper, 3.0 + 2.776445 * std::sqrt(0.5), 1e-5);
}

// Drawn many times, the interval of 8 normal values holds their expectation 95 % of the time:
// 4 000 intervals, within four binomial standard errors (0.0034 each) of 0.95.
TEST(RunMeanInterval, HoldsTheExpectationAtItsConfidence) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> value(1.0, 0.3);
  int held = 0;
  const int trials = 4000;
  for (int trial = 0; trial < trials; ++trial) {
    std::vector<double> values(8);
    for (double& v : values) v = value(rng);
    held += run_mean_interval(values).contains(1.0) ? 1 : 0;
  }
  EXPECT_NEAR(held / static_cast<double>(trials), 0.95, 4.0 * 0.0034);
}

TEST(RunMeanInterval, OneValueBoundsNothingAndNoValueIsRefused) {
  const RunMeanInterval one = run_mean_interval({1.5});
  EXPECT_DOUBLE_EQ(one.mean, 1.5);
  EXPECT_TRUE(std::isinf(one.lower) && one.lower < 0.0);
  EXPECT_TRUE(std::isinf(one.upper) && one.upper > 0.0);
  EXPECT_THROW(run_mean_interval({}), std::invalid_argument);
  EXPECT_THROW(run_mean_interval({1.0, 2.0}, 1.0), std::invalid_argument);
  EXPECT_THROW(student_t_quantile(0.5, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace skyfuse
