#include "skyfuse/registration/considered_biases.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <random>
#include <string>

#include "skyfuse/fusion/increment_fusion.hpp"
#include "skyfuse/models/position_sensor.hpp"

namespace skyfuse {
namespace {

constexpr int N = 6;
using Sensor = PositionSensor<N>;

Covariance<3> isotropic(double std) {
  return Covariance<3>::Identity() * std * std;
}

Covariance<N> constant_velocity(double dt) {
  Covariance<N> f = Covariance<N>::Identity();
  f.topRightCorner<3, 3>() = Matrix3::Identity() * dt;
  return f;
}

GaussianState<N> some_prior() {
  GaussianState<N> prior;
  prior.mean << 100.0, -50.0, 300.0, 20.0, -5.0, 1.0;
  Matrix<N, N> a = Matrix<N, N>::Identity() * 3.0;
  a(0, 3) = 1.5;
  a(1, 4) = -0.7;
  a(2, 0) = 0.4;
  prior.covariance = a * a.transpose();
  return prior;
}

// The joint [x; u] of a prior and its C̃, as a covariance.
Eigen::MatrixXd joint_prior(const GaussianState<N>& prior, const ConsideredCross& cross) {
  const Eigen::Index d = cross.cols();
  Eigen::MatrixXd joint = Eigen::MatrixXd::Identity(N + d, N + d);
  joint.topLeftCorner(N, N) = prior.covariance;
  joint.topRightCorner(N, d) = cross;
  joint.bottomLeftCorner(d, N) = cross.transpose();
  return joint;
}

TEST(ConsideredBiases, IsTheJointKalmanUpdatesPartOfTheTrack) {
  // A registered station (a position offset, standardised: G̃ = L) whose error the track
  // already carries, and an unregistered one: the information form against the covariance
  // form of the joint update, the Schmidt–Kalman filter's x-part.
  const GaussianState<N> prior = some_prior();
  Matrix3 l = Matrix3::Zero();
  l.diagonal() << 4.0, 2.0, 3.0;
  l(1, 0) = 0.5;
  ConsideredCross held = ConsideredCross::Zero(N, 3);
  held(0, 0) = 1.2;
  held(1, 1) = -0.6;
  held(3, 0) = 0.3;
  ConsideredBiases considered{{1, held}};

  const Sensor sensor;
  const Vector<3> z1(104.0, -47.0, 296.0);
  const Vector<3> z2(99.0, -52.0, 305.0);
  const Covariance<3> r1 = isotropic(2.0);
  const Covariance<3> r2 = isotropic(5.0);

  InformationIncrement<N> i1, i2;
  ASSERT_EQ(compute_increment(1, prior, sensor, z1, r1, i1), NumericalStatus::kOk);
  ASSERT_EQ(compute_increment(2, prior, sensor, z2, r2, i2), NumericalStatus::kOk);
  ConsideredTerms t1;
  ASSERT_TRUE(considered_terms(1, prior, sensor, z1, r1, Matrix<3, Eigen::Dynamic>(l), t1));
  const std::vector<InformationIncrement<N>> increments{i1, i2};
  const std::vector<double> ones{1.0, 1.0};
  GaussianState<N> fused = prior;
  ASSERT_EQ(fuse_considered(fused, considered, std::span(increments), ones,
                            std::span<const ConsideredTerms>(&t1, 1), std::span(ones).first(1)),
            NumericalStatus::kOk);

  // The covariance form: K = Π Aᵀ (A Π Aᵀ + R)⁻¹ over the stacked [z1; z2].
  const Eigen::MatrixXd joint = joint_prior(prior, held);
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(6, N + 3);
  a.block(0, 0, 3, N) = sensor.jacobian(prior.mean);
  a.block(0, N, 3, 3) = l;
  a.block(3, 0, 3, N) = sensor.jacobian(prior.mean);
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(6, 6);
  r.topLeftCorner(3, 3) = r1;
  r.bottomRightCorner(3, 3) = r2;
  Eigen::VectorXd innovation(6);
  innovation << z1 - prior.mean.head<3>(), z2 - prior.mean.head<3>();
  const Eigen::MatrixXd s = a * joint * a.transpose() + r;
  const Eigen::MatrixXd gain = joint * a.transpose() * s.inverse();
  const Eigen::MatrixXd posterior = joint - gain * s * gain.transpose();
  const Eigen::VectorXd x = prior.mean + (gain * innovation).head(N);

  EXPECT_LT((fused.mean - x).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((fused.covariance - posterior.topLeftCorner(N, N)).cwiseAbs().maxCoeff(), 1e-9);
  ASSERT_EQ(considered.size(), 1U);
  EXPECT_EQ(considered[0].station_id, 1);
  EXPECT_LT((considered[0].cross - posterior.topRightCorner(N, 3)).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(ConsideredBiases, ATrackHoldingNoneFusesAsTheIncrementsDo) {
  const GaussianState<N> prior = some_prior();
  InformationIncrement<N> i2;
  ASSERT_EQ(
      compute_increment(2, prior, Sensor{}, Vector<3>(99.0, -52.0, 305.0), isotropic(5.0), i2),
      NumericalStatus::kOk);
  const std::vector<InformationIncrement<N>> increments{i2};
  const std::vector<double> weight{0.7};
  GaussianState<N> plain;
  ASSERT_EQ(fuse_increments(prior, std::span(increments), weight, plain), NumericalStatus::kOk);
  GaussianState<N> considered_state = prior;
  ConsideredBiases none;
  ASSERT_EQ(fuse_considered(considered_state, none, std::span(increments), weight, {}, {}),
            NumericalStatus::kOk);
  EXPECT_TRUE(none.empty());
  EXPECT_LT((considered_state.mean - plain.mean).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((considered_state.covariance - plain.covariance).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(ConsideredBiases, AStationNewToTheTrackStartsUncorrelated) {
  // C̃ = 0 before: the joint update gives −P⁺ Hᵀ (R + G̃G̃ᵀ)⁻¹ G̃, the cross-covariance of the
  // update's error with the bias it could not see.
  const GaussianState<N> prior = some_prior();
  const Sensor sensor;
  const Vector<3> z(104.0, -47.0, 296.0);
  const Covariance<3> r = isotropic(2.0);
  const Matrix3 l = Matrix3::Identity() * 3.0;
  InformationIncrement<N> increment;
  ASSERT_EQ(compute_increment(4, prior, sensor, z, r, increment), NumericalStatus::kOk);
  ConsideredTerms terms;
  ASSERT_TRUE(considered_terms(4, prior, sensor, z, r, Matrix<3, Eigen::Dynamic>(l), terms));
  ConsideredBiases considered;
  GaussianState<N> fused = prior;
  const std::vector<double> one{1.0};
  ASSERT_EQ(fuse_considered(fused, considered, std::span(&increment, 1), one,
                            std::span<const ConsideredTerms>(&terms, 1), one),
            NumericalStatus::kOk);
  ASSERT_EQ(considered.size(), 1U);
  EXPECT_EQ(considered[0].station_id, 4);
  // The white treatment's posterior is the same here (one detection, no history).
  const Matrix<3, N> h = sensor.jacobian(prior.mean);
  const Covariance<3> white = r + l * l.transpose();
  const Covariance<N> p =
      (prior.covariance.inverse() + h.transpose() * white.inverse() * h).inverse();
  EXPECT_LT((fused.covariance - p).cwiseAbs().maxCoeff(), 1e-9);
  const Matrix<N, 3> expected = -p * h.transpose() * white.inverse() * l;
  EXPECT_LT((considered[0].cross - expected).cwiseAbs().maxCoeff(), 1e-9);
}

// One Monte Carlo run of a track that a biased station (its bias unknown, ~N(0, Σ), the same in
// every detection) and an aligned one update for `steps` rounds: the track's NEES at the end.
// `schmidt` false: the bias taken as white noise, R + Σ in every detection.
double final_nees(bool schmidt, std::mt19937_64& rng, int steps) {
  std::normal_distribution<double> normal;
  const auto draw = [&](double std) {
    return Vector<3>(std * normal(rng), std * normal(rng), std * normal(rng));
  };
  const double bias_std = 30.0;
  const Covariance<3> r1 = isotropic(10.0);
  const Covariance<3> r2 = isotropic(60.0);
  const Covariance<N> f = constant_velocity(1.0);
  const Sensor sensor;

  GaussianState<N> track;
  track.mean.setZero();
  track.covariance = Covariance<N>::Identity() * 100.0;
  Vector<N> truth;
  truth << draw(10.0), draw(10.0);
  const Vector<3> bias = draw(bias_std);
  const Matrix<3, Eigen::Dynamic> g_scaled = Matrix3::Identity() * bias_std;
  ConsideredBiases considered;

  for (int k = 0; k < steps; ++k) {
    truth = (f * truth).eval();
    predict_considered(f, considered);
    track.mean = (f * track.mean).eval();
    track.covariance = (f * track.covariance * f.transpose()).eval();
    const Vector<3> z1 = truth.head<3>() + bias + draw(10.0);
    const Vector<3> z2 = truth.head<3>() + draw(60.0);
    std::vector<InformationIncrement<N>> increments(2);
    const Covariance<3> r1_used = schmidt ? r1 : Covariance<3>(r1 + isotropic(bias_std));
    EXPECT_EQ(compute_increment(1, track, sensor, z1, r1_used, increments[0]),
              NumericalStatus::kOk);
    EXPECT_EQ(compute_increment(2, track, sensor, z2, r2, increments[1]), NumericalStatus::kOk);
    const std::vector<double> ones{1.0, 1.0};
    if (schmidt) {
      ConsideredTerms terms;
      EXPECT_TRUE(considered_terms(1, track, sensor, z1, r1, g_scaled, terms));
      EXPECT_EQ(
          fuse_considered(track, considered, std::span(increments), ones,
                          std::span<const ConsideredTerms>(&terms, 1), std::span(ones).first(1)),
          NumericalStatus::kOk);
    } else {
      EXPECT_EQ(fuse_increments(track, std::span(increments), ones, track), NumericalStatus::kOk);
    }
  }
  const Vector<N> error = truth - track.mean;
  return error.dot(track.covariance.ldlt().solve(error));
}

TEST(ConsideredBiases, KeepTheTrackConsistentWhereWhiteNoiseDoesNot) {
  // 400 runs of 40 rounds: the average NEES per degree of freedom against χ²(2400)/2400's
  // 0.999 band (Wilson–Hilferty), [0.908, 1.098]. Taken as white noise, the bias makes the track
  // believe it averaged away what every detection shares.
  constexpr int kRuns = 400;
  std::mt19937_64 rng(20261201);
  double schmidt = 0.0;
  double white = 0.0;
  for (int run = 0; run < kRuns; ++run) {
    schmidt += final_nees(true, rng, 40);
    white += final_nees(false, rng, 40);
  }
  schmidt /= kRuns * N;
  white /= kRuns * N;
  RecordProperty("schmidt_anees", std::to_string(schmidt));
  RecordProperty("white_anees", std::to_string(white));
  EXPECT_GT(schmidt, 0.908);
  EXPECT_LT(schmidt, 1.098);
  EXPECT_GT(white, 2.0) << "the test cannot tell the two treatments apart";
}

}  // namespace
}  // namespace skyfuse
