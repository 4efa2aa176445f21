// The planar models of paper 001: each analytic transition Jacobian against central
// differences, the corrected coordinated-turn matrix, and the process noises' definiteness.

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>

#include "skyfuse/filters/kalman.hpp"
#include "skyfuse/models/planar/constant_acceleration_2d.hpp"
#include "skyfuse/models/planar/constant_velocity_2d.hpp"
#include "skyfuse/models/planar/coordinated_turn_2d.hpp"
#include "skyfuse/models/planar/position_2d.hpp"
#include "skyfuse/models/planar/turn_rate_velocity_2d.hpp"
#include "skyfuse/random/counter_rng.hpp"
#include "support/draw_last_first.hpp"

namespace skyfuse {
namespace {

constexpr double kDt = 0.1;
constexpr double kSigmaQ2 = 10.0;

template <typename Model>
Covariance<Model::kDim> numerical_transition_jacobian(const Model& model,
                                                      const Vector<Model::kDim>& x) {
  Covariance<Model::kDim> j;
  for (int i = 0; i < Model::kDim; ++i) {
    const double step = 1e-6 * std::max(1.0, std::abs(x(i)));
    Vector<Model::kDim> plus = x;
    Vector<Model::kDim> minus = x;
    plus(i) += step;
    minus(i) -= step;
    j.col(i) = (model.propagate(plus) - model.propagate(minus)) / (2.0 * step);
  }
  return j;
}

template <typename Model>
void expect_jacobian_matches_differences(const Model& model, const Vector<Model::kDim>& x) {
  const Covariance<Model::kDim> analytic = model.jacobian(x);
  const Covariance<Model::kDim> numeric = numerical_transition_jacobian(model, x);
  EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff(), 1e-7)
      << "at x = " << x.transpose() << "\nanalytic\n"
      << analytic << "\nnumeric\n"
      << numeric;
}

double smallest_eigenvalue(const Eigen::MatrixXd& m) {
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(m).eigenvalues().minCoeff();
}

TEST(ConstantVelocity2D, SteadyStateMatchesPaper001) {
  // SEEDS.md: per axis P_pos = 1.216 m^2 and gain (0.135, 0.098) at sigma_Q^2 = 10, R = 9.
  const ConstantVelocity2D model(kDt, kSigmaQ2);
  GaussianState<4> state;
  const Covariance<2> r = 9.0 * Covariance<2>::Identity();
  for (int k = 0; k < 2000; ++k) {
    predict(state, model);
    update(state, Position2D<ConstantVelocity2D>{}, Vector<2>::Zero(), r);
  }
  EXPECT_NEAR(state.covariance(0, 0), 1.216, 5e-4);
  EXPECT_NEAR(state.covariance(2, 2), 1.216, 5e-4);
  // The posterior gain K = P+ H^T R^-1.
  EXPECT_NEAR(state.covariance(0, 0) / 9.0, 0.135, 5e-4);
  EXPECT_NEAR(state.covariance(1, 0) / 9.0, 0.098, 5e-4);
}

TEST(ConstantVelocity2D, ProcessNoiseIsPiecewiseConstantAcceleration) {
  const ConstantVelocity2D model(kDt, kSigmaQ2);
  const Covariance<4> q = model.process_noise();
  EXPECT_DOUBLE_EQ(q(0, 0), kSigmaQ2 * std::pow(kDt, 4) / 4.0);
  EXPECT_DOUBLE_EQ(q(0, 1), kSigmaQ2 * std::pow(kDt, 3) / 2.0);
  EXPECT_DOUBLE_EQ(q(3, 3), kSigmaQ2 * kDt * kDt);
  EXPECT_EQ(q(0, 2), 0.0);
  EXPECT_GE(smallest_eigenvalue(q), -1e-18);
}

TEST(ConstantAcceleration2D, PropagatesWithConstantAccelerationAndPositiveNoise) {
  const ConstantAcceleration2D model(kDt, kSigmaQ2);
  Vector<6> x;
  x << 1.0, 2.0, 3.0, -4.0, 5.0, -6.0;
  const Vector<6> next = model.propagate(x);
  EXPECT_DOUBLE_EQ(next(0), 1.0 + 2.0 * kDt + 3.0 * kDt * kDt / 2.0);
  EXPECT_DOUBLE_EQ(next(1), 2.0 + 3.0 * kDt);
  EXPECT_DOUBLE_EQ(next(4), 5.0 - 6.0 * kDt);
  expect_jacobian_matches_differences(model, x);
  EXPECT_GT(smallest_eigenvalue(model.process_noise()), 0.0);
}

TEST(CoordinatedTurn2D, TurnsTheVelocityByOmegaDt) {
  // The corrected eq 25: after one step the speed is unchanged and the heading has turned by
  // omega dt. With the printed matrix the velocity would not turn at all.
  const CoordinatedTurn2D model(kDt, kSigmaQ2);
  Vector<5> x;
  x << 0.0, 20.0, 0.0, 0.0, 0.5;
  const Vector<5> next = model.propagate(x);
  EXPECT_NEAR(std::hypot(next(1), next(3)), 20.0, 1e-12);
  EXPECT_NEAR(std::atan2(next(3), next(1)), 0.5 * kDt, 1e-12);
  // Position on the arc of radius v / omega: (R sin(w dt), R (1 - cos(w dt))).
  EXPECT_NEAR(next(0), 40.0 * std::sin(0.05), 1e-12);
  EXPECT_NEAR(next(2), 40.0 * (1.0 - std::cos(0.05)), 1e-12);
}

TEST(CoordinatedTurn2D, JacobianMatchesDifferencesTurningAndStraight) {
  const CoordinatedTurn2D model(kDt, kSigmaQ2);
  for (const double omega : {0.7, -0.3, 1e-3, 0.0}) {
    Vector<5> x;
    x << 10.0, 12.0, -5.0, 7.0, omega;
    expect_jacobian_matches_differences(model, x);
  }
}

TEST(CoordinatedTurn2D, StraightLimitIsContinuous) {
  const CoordinatedTurn2D model(kDt, kSigmaQ2);
  Vector<5> straight;
  straight << 1.0, 12.0, 2.0, 7.0, 0.0;
  // Either side of where the d/d omega terms switch to their series, and at omega = 0.
  for (const double omega : {0.0, 0.99e-2, 1.01e-2, 1e-9}) {
    Vector<5> x = straight;
    x(4) = omega;
    expect_jacobian_matches_differences(model, x);
  }
  Vector<5> barely = straight;
  barely(4) = 1e-12;
  // The only difference is the physical turn, omega dt v = 1.2e-12 here.
  EXPECT_LT((model.propagate(straight) - model.propagate(barely)).cwiseAbs().maxCoeff(), 2e-12);
}

TEST(TurnRateVelocity2D, JacobianMatchesDifferences) {
  const TurnRateVelocity2D model(kDt, kSigmaQ2);
  for (const double heading : {0.3, 2.0, -2.8}) {
    Vector<5> x;
    x << 4.0, -3.0, heading, 17.0, 0.4;
    expect_jacobian_matches_differences(model, x);
  }
}

TEST(TurnRateVelocity2D, PrintedProcessNoiseIsIndefiniteAndTheDefaultIsNot) {
  Vector<5> x;
  x << 0.0, 0.0, 0.7, 15.0, 0.1;
  const TurnRateVelocity2D printed(kDt, kSigmaQ2, TurnRateNoise::kPrinted);
  // SEEDS.md: lambda_min about -2.5e-4 at dt = 0.1, sigma_Q^2 = 10.
  EXPECT_NEAR(smallest_eigenvalue(printed.process_noise(x)), -2.5e-4, 0.1e-4);
  const TurnRateVelocity2D sound(kDt, kSigmaQ2);
  EXPECT_GE(smallest_eigenvalue(sound.process_noise(x)), -1e-15);
}

TEST(TurnRateVelocity2D, FilterCovarianceStaysSymmetricPositiveDefinite) {
  // A turning target tracked from noisy positions: with the default noise P stays SPD.
  const TurnRateVelocity2D model(kDt, kSigmaQ2);
  GaussianState<5> state;
  state.mean << 0.0, 0.0, 0.0, 15.0, 0.0;
  const Covariance<2> r = 9.0 * Covariance<2>::Identity();
  Vector<5> truth = state.mean;
  truth(4) = 0.3;
  CounterRng rng(NoiseKey{1, 0, 0, 0, NoiseStream::kMeasurement});
  for (int k = 0; k < 300; ++k) {
    truth = model.propagate(truth);
    predict(state, model);
    const Vector<2> z =
        truth.head<2>() + 3.0 * test::draw_last_first<2>([&] { return rng.normal(); });
    ASSERT_EQ(update(state, Position2D<TurnRateVelocity2D>{}, z, r).status, NumericalStatus::kOk);
    ASSERT_EQ(state.covariance, state.covariance.transpose());
    ASSERT_GT(smallest_eigenvalue(state.covariance), 0.0) << "step " << k;
  }
  EXPECT_NEAR(state.mean(4), 0.3, 3.0 * std::sqrt(state.covariance(4, 4)));
}

TEST(Position2D, ReadsEachModelsOwnPositionIndices) {
  Vector<6> ca;
  ca << 1.0, 2.0, 3.0, 4.0, 5.0, 6.0;
  EXPECT_EQ(Position2D<ConstantAcceleration2D>::predict(ca), Vector<2>(1.0, 4.0));
  Vector<5> ctrv;
  ctrv << 1.0, 2.0, 3.0, 4.0, 5.0;
  EXPECT_EQ(Position2D<TurnRateVelocity2D>::predict(ctrv), Vector<2>(1.0, 2.0));
  const Jacobian<2, 5> h = Position2D<CoordinatedTurn2D>::jacobian(ctrv);
  EXPECT_EQ(h(0, 0), 1.0);
  EXPECT_EQ(h(1, 2), 1.0);
  EXPECT_EQ(h.sum(), 2.0);
}

}  // namespace
}  // namespace skyfuse
