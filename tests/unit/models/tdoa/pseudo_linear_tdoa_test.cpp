// Paper 002's measurement: the pseudo-linear identity (Eq 3) on random geometry, the bias
// statistics W and V against a Monte-Carlo estimate, and the range-difference sensor's Jacobian.
#include "skyfuse/models/tdoa/pseudo_linear_tdoa.hpp"

#include <gtest/gtest.h>

#include <random>

#include "skyfuse/models/tdoa/range_difference_sensor.hpp"
#include "support/draw_last_first.hpp"
#include "support/numerical_jacobian.hpp"

namespace skyfuse {
namespace {

// [dx, dy, d_t1, 0...] of a target at `relative` = p_t - p_1.
Vector<9> state_of(const Vector<2>& relative) {
  Vector<9> x = Vector<9>::Zero();
  x << relative.x(), relative.y(), relative.norm(), 0.0, 0.0, 0.0, 0.0, 0.0, 0.0;
  return x;
}

TEST(PseudoLinearTdoa, TheSquaredRangeDifferenceIsLinearInTheStateOnRandomGeometry) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-5000.0, 5000.0);
  for (int trial = 0; trial < 1000; ++trial) {
    const Vector<2> target = test::draw_last_first<2>([&] { return coordinate(rng); });
    const Vector<2> offset = test::draw_last_first<2>([&] { return coordinate(rng) / 10.0; });
    const double r = range_difference(target, offset);
    // Without noise (sigma 0) y_j = r_j^2 - d_j1^2 and H_j x = -2 [P_j, r_j] [dp, d_t1] (Eq 3).
    const PseudoLinearTdoaRow row = pseudo_linear_tdoa_row(offset, r, r, 0.0);
    // Both sides are differences of terms up to ~1e7: the rounding is relative to those.
    const Vector<9> x = state_of(target);
    const double scale = row.h.cwiseAbs().dot(x.cwiseAbs()) + target.squaredNorm();
    EXPECT_NEAR(row.h.dot(x), row.y, 1e-12 * scale) << "trial " << trial;
  }
}

// Monte-Carlo mean and standard error of f(dr) over dr ~ N(0, sigma^2).
template <typename F>
std::pair<double, double> monte_carlo(double sigma, F f) {
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, sigma);
  constexpr int kDraws = 400000;
  double sum = 0.0;
  double sum_sq = 0.0;
  for (int i = 0; i < kDraws; ++i) {
    const double value = f(noise(rng));
    sum += value;
    sum_sq += value * value;
  }
  const double mean = sum / kDraws;
  return {mean, std::sqrt((sum_sq / kDraws - mean * mean) / kDraws)};
}

TEST(PseudoLinearTdoa, WAndVAreTheBiasStatisticsByMonteCarlo) {
  // A target 3 km out near the perpendicular bisector of UAV 1 and a receiver 200 m from it:
  // r_j = 1.33 m, where V is large enough for the Monte Carlo to tell it from the printed one.
  const Vector<2> target(3000.0, 80.0);
  const Vector<2> offset(0.0, 200.0);
  const double sigma = 0.4;
  const double r = range_difference(target, offset);
  const Vector<9> x = state_of(target);
  const PseudoLinearTdoaRow exact = pseudo_linear_tdoa_row(offset, r, r, sigma);
  const auto noisy_row = [&](double dr) {
    return pseudo_linear_tdoa_row(offset, r + dr, r + dr, sigma);
  };

  // W = E[H~^T R^-1 H~] - H^T R^-1 H, in its (3, 3) entry (R at the true r).
  const auto [w, w_error] = monte_carlo(sigma, [&](double dr) {
    const double h3 = noisy_row(dr).h(2);
    return (h3 * h3 - exact.h(2) * exact.h(2)) / exact.noise;
  });
  EXPECT_NEAR(w, exact.w, 4.0 * w_error);

  // V = E[H~^T R^-1 v], v = 2 r dr + dr^2 - sigma^2, in its third entry.
  const auto [v, v_error] = monte_carlo(sigma, [&](double dr) {
    return noisy_row(dr).h(2) * (2.0 * r * dr + dr * dr - sigma * sigma) / exact.noise;
  });
  EXPECT_NEAR(v, exact.v, 4.0 * v_error);
  const double printed_v = -2.0 / (2.0 * r * r + sigma * sigma);  // without r_j on top
  EXPECT_GT(std::abs(printed_v - v), 10.0 * v_error);

  // Together: E[H~^T R^-1 (y - H~ x)] = V - W x, the nominal filter's bias, in d_t1 only.
  const auto [bias, bias_error] = monte_carlo(sigma, [&](double dr) {
    const PseudoLinearTdoaRow row = noisy_row(dr);
    return row.h(2) * (row.y - row.h.dot(x)) / exact.noise;
  });
  EXPECT_NEAR(bias, exact.v - exact.w * x(2), 4.0 * bias_error);
  EXPECT_GT(std::abs(exact.v - exact.w * x(2)), 20.0 * bias_error);
  const auto [first, first_error] = monte_carlo(sigma, [&](double dr) {
    const PseudoLinearTdoaRow row = noisy_row(dr);
    return row.h(0) * (row.y - row.h.dot(x)) / exact.noise;
  });
  EXPECT_NEAR(first, 0.0, 4.0 * first_error);
}

TEST(PseudoLinearTdoa, RIsTheVarianceOfThePseudoLinearNoise) {
  const double sigma = 0.4;
  const double r = 37.5;
  // v = 2 r dr + dr^2 - sigma^2 has mean 0, so its variance is E[v^2].
  const auto [second_moment, error] = monte_carlo(sigma, [&](double dr) {
    const double v = 2.0 * r * dr + dr * dr - sigma * sigma;
    return v * v;
  });
  const PseudoLinearTdoaRow row = pseudo_linear_tdoa_row(Vector<2>(200.0, 0.0), r, r, sigma);
  EXPECT_NEAR(second_moment, row.noise, 4.0 * error);
}

TEST(RangeDifferenceSensor, AnalyticJacobianEqualsCentralDifferences) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> coordinate(-4000.0, 4000.0);
  const RangeDifferenceSensor<6> sensor(Vector<2>(-200.0, 150.0));
  for (int trial = 0; trial < 100; ++trial) {
    Vector<6> x = Vector<6>::Zero();
    x << coordinate(rng), coordinate(rng), 3.0, -2.0, 0.1, 0.0;
    const auto analytic = sensor.jacobian(x);
    const auto numeric = test::numerical_jacobian(sensor, x);
    EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff(), 1e-7) << "trial " << trial;
    EXPECT_NEAR(sensor.predict(x)(0), range_difference(x.head<2>(), sensor.offset()), 1e-12);
  }
}

}  // namespace
}  // namespace skyfuse
