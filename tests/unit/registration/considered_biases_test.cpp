#include "skyfuse/registration/considered_biases.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cstdio>
#include <random>
#include <string>
#include <utility>

#include "skyfuse/fusion/increment_fusion.hpp"
#include "skyfuse/metrics/chi_square.hpp"
#include "skyfuse/models/position_sensor.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/picture/track_table.hpp"
#include "skyfuse/registration/considered_terms_impl.hpp"
#include "skyfuse/registration/station_bias.hpp"
#include "support/draw_last_first.hpp"

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

// One Monte Carlo run of a track that a biased station (its bias unknown, ~N(0, 30² m²), the
// same in every detection) and an aligned one update round by round.
class BiasedRun {
 public:
  static constexpr double kBiasStd = 30.0;

  explicit BiasedRun(std::mt19937_64& rng) : rng_(rng) {
    track_.mean.setZero();
    track_.covariance = Covariance<N>::Identity() * 100.0;
    truth_ << draw(10.0), draw(10.0);
    bias_ = draw(kBiasStd);
  }

  Vector<3> draw(double std) {
    return std * test::draw_last_first<3>([&] { return normal_(rng_); });
  }
  const Vector<3>& bias() const { return bias_; }
  GaussianState<N>& track() { return track_; }
  ConsideredBiases& considered() { return considered_; }

  // The next round: truth, track and C̃ predicted; the biased station's detection, less
  // `correction` (its registration's settled estimate), and the aligned one's, fused — with the
  // biased one's terms for G̃ = `g_scaled`, or (`g_scaled` empty) with R + 30² I for its bias.
  void round(const Vector<3>& correction, const Eigen::MatrixXd& g_scaled) {
    truth_ = (f_ * truth_).eval();
    predict_considered(f_, considered_);
    track_.mean = (f_ * track_.mean).eval();
    track_.covariance = (f_ * track_.covariance * f_.transpose()).eval();
    const Vector<3> z1 = truth_.head<3>() + bias_ + draw(10.0) - correction;
    const Vector<3> z2 = truth_.head<3>() + draw(60.0);
    const bool schmidt = g_scaled.size() > 0;
    std::vector<InformationIncrement<N>> increments(2);
    const Covariance<3> r1_used = schmidt ? r1_ : Covariance<3>(r1_ + isotropic(kBiasStd));
    EXPECT_EQ(compute_increment(1, track_, sensor_, z1, r1_used, increments[0]),
              NumericalStatus::kOk);
    EXPECT_EQ(compute_increment(2, track_, sensor_, z2, r2_, increments[1]), NumericalStatus::kOk);
    const std::vector<double> ones{1.0, 1.0};
    if (schmidt) {
      ConsideredTerms terms;
      EXPECT_TRUE(considered_terms(1, track_, sensor_, z1, r1_, g_scaled, terms));
      EXPECT_EQ(
          fuse_considered(track_, considered_, std::span(increments), ones,
                          std::span<const ConsideredTerms>(&terms, 1), std::span(ones).first(1)),
          NumericalStatus::kOk);
    } else {
      EXPECT_EQ(fuse_increments(track_, std::span(increments), ones, track_), NumericalStatus::kOk);
    }
  }

  double nees() const {
    const Vector<N> error = truth_ - track_.mean;
    return error.dot(track_.covariance.ldlt().solve(error));
  }

 private:
  std::mt19937_64& rng_;
  std::normal_distribution<double> normal_;
  const Covariance<3> r1_ = isotropic(10.0);
  const Covariance<3> r2_ = isotropic(60.0);
  const Covariance<N> f_ = constant_velocity(1.0);
  const Sensor sensor_{};
  GaussianState<N> track_;
  Vector<N> truth_;
  Vector<3> bias_;
  ConsideredBiases considered_;
};

// A BiasedRun of `steps` rounds, its track's NEES at the end. `schmidt` false: the bias taken
// as white noise, R + Σ in every detection.
double final_nees(bool schmidt, std::mt19937_64& rng, int steps) {
  BiasedRun run(rng);
  const Eigen::MatrixXd g_scaled =
      schmidt ? Eigen::MatrixXd(Matrix3::Identity() * BiasedRun::kBiasStd) : Eigen::MatrixXd();
  for (int k = 0; k < steps; ++k) run.round(Vector<3>::Zero(), g_scaled);
  return run.nees();
}

// The ANEES per dof of two rules' final NEES, `first(rng)` and `second(rng)`, over `runs` runs of
// each, alternating on one generator seeded `seed`.
template <typename First, typename Second>
std::pair<double, double> paired_anees(int runs, std::uint64_t seed, First first, Second second) {
  std::mt19937_64 rng(seed);
  double a = 0.0;
  double b = 0.0;
  for (int run = 0; run < runs; ++run) {
    a += first(rng);
    b += second(rng);
  }
  return {a / (runs * N), b / (runs * N)};
}

TEST(ConsideredBiases, KeepTheTrackConsistentWhereWhiteNoiseDoesNot) {
  // 400 runs of 40 rounds: the average NEES per degree of freedom against χ²(2400)/2400's
  // 0.999 band (Wilson–Hilferty), [0.908, 1.098]. Taken as white noise, the bias makes the track
  // believe it averaged away what every detection shares.
  const auto [schmidt, white] = paired_anees(
      400, 20261201, [](std::mt19937_64& rng) { return final_nees(true, rng, 40); },
      [](std::mt19937_64& rng) { return final_nees(false, rng, 40); });
  RecordProperty("schmidt_anees", std::to_string(schmidt));
  RecordProperty("white_anees", std::to_string(white));
  EXPECT_GT(schmidt, 0.908);
  EXPECT_LT(schmidt, 1.098);
  EXPECT_GT(white, 2.0) << "the test cannot tell the two treatments apart";
}

// What a track does when its station's registration settles.
enum class AtSettle {
  kCondition,  // settle_considered: x̂ += C̃ m, P −= C̃ (I − A Aᵀ) C̃ᵀ, C̃ ← C̃ A
  kMoveOnly,   // x̂ += C̃ m, P and C̃ kept (the picture's rule before settle_considered)
};

// A BiasedRun whose biased station is registered: its biases learnt each round from a reference
// of their own (y = b + w, w ~ N(0, 5² I), independent of the track), its detections corrected
// by the settled b̂, its G̃ the settled L, and the track told of each settle by `at_settle`. The
// track's NEES at the end.
double final_nees_registered(AtSettle at_settle, std::mt19937_64& rng, int steps) {
  const double reference_std = 5.0;
  BiasedRun run(rng);
  // The registration: information and vector of b, its settled estimate and factor.
  Matrix3 information = Matrix3::Identity() / (BiasedRun::kBiasStd * BiasedRun::kBiasStd);
  Vector3 vector = Vector3::Zero();
  Vector3 settled = Vector3::Zero();
  Matrix3 factor = Matrix3::Identity() * BiasedRun::kBiasStd;
  for (int k = 0; k < steps; ++k) {
    run.round(settled, Eigen::MatrixXd(factor));
    // The registration learns from its reference and settles.
    information += Matrix3::Identity() / (reference_std * reference_std);
    vector += (run.bias() + run.draw(reference_std)) / (reference_std * reference_std);
    const Eigen::LLT<Matrix3> solved(information);
    const Vector3 next = solved.solve(vector);
    const Matrix3 next_factor = Matrix3(solved.solve(Matrix3::Identity())).llt().matrixL();
    const Eigen::VectorXd move = factor.triangularView<Eigen::Lower>().solve(next - settled);
    const Eigen::MatrixXd narrowing = factor.triangularView<Eigen::Lower>().solve(next_factor);
    for (ConsideredBias& c : run.considered()) {
      if (at_settle == AtSettle::kCondition) {
        settle_considered(run.track(), c, move, narrowing);
      } else {
        run.track().mean.noalias() += c.cross * move;
      }
    }
    settled = next;
    factor = next_factor;
  }
  return run.nees();
}

TEST(ConsideredBiases, ATrackConditionedOnEachSettleStaysConsistent) {
  // 2 000 runs of 40 rounds: the average NEES per degree of freedom against χ²(12000)/12000's
  // 0.999 band. Moving the mean alone leaves the track holding a C̃ against errors the
  // registration has since narrowed, and an uncertainty it has resolved: not the joint's.
  constexpr int kRuns = 2000;
  const auto [conditioned, moved_only] = paired_anees(
      kRuns, 20261202,
      [](std::mt19937_64& rng) { return final_nees_registered(AtSettle::kCondition, rng, 40); },
      [](std::mt19937_64& rng) { return final_nees_registered(AtSettle::kMoveOnly, rng, 40); });
  const double samples = kRuns * N;
  const double low = chi_square_quantile(0.0005, samples) / samples;
  const double high = chi_square_quantile(0.9995, samples) / samples;
  std::printf("ANEES per dof: conditioned %.3f, mean moved only %.3f; band [%.3f, %.3f]\n",
              conditioned, moved_only, low, high);
  EXPECT_GT(conditioned, low);
  EXPECT_LT(conditioned, high);
  EXPECT_TRUE(moved_only < low || moved_only > high)
      << moved_only << ": the test cannot tell the two rules apart";
}

// The conditioning itself: the joint Gaussian's, computed the long way.
TEST(ConsideredBiases, SettlingIsTheJointGaussiansConditioning) {
  GaussianState<N> track = some_prior();
  ConsideredBias c{4, ConsideredCross(N, 3)};
  c.cross << 1.0, 0.2, -0.3, 0.5, -1.1, 0.4, 0.0, 0.7, 0.9, 0.3, 0.1, -0.2, -0.4, 0.2, 0.1, 0.6,
      0.0, 0.3;
  c.cross *= 0.8;
  Eigen::MatrixXd narrowing(3, 3);
  narrowing << 0.6, 0.0, 0.0, 0.1, 0.5, 0.0, -0.2, 0.05, 0.7;
  const Eigen::VectorXd move = Eigen::Vector3d(0.3, -1.2, 0.5);
  // u's posterior N(m, A Aᵀ) as a measurement y = u + v, v ~ N(0, V): V = (S⁻¹ − I)⁻¹,
  // y = (I + V) m, with S = A Aᵀ.
  const Eigen::MatrixXd s = narrowing * narrowing.transpose();
  const Eigen::MatrixXd v = (s.inverse() - Eigen::MatrixXd::Identity(3, 3)).inverse();
  const Eigen::VectorXd y = (Eigen::MatrixXd::Identity(3, 3) + v) * move;
  const Eigen::MatrixXd joint = joint_prior(track, c.cross);
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(3, N + 3);
  h.rightCols(3).setIdentity();
  const Eigen::MatrixXd gain = joint * h.transpose() * (h * joint * h.transpose() + v).inverse();
  Eigen::VectorXd joint_mean = Eigen::VectorXd::Zero(N + 3);
  joint_mean.head(N) = track.mean;
  joint_mean += gain * (y - h * joint_mean);
  const Eigen::MatrixXd posterior = joint - gain * h * joint;

  settle_considered(track, c, move, narrowing);
  EXPECT_LT((track.mean - joint_mean.head(N)).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((track.covariance - posterior.topLeftCorner(N, N)).cwiseAbs().maxCoeff(), 1e-9);
  // Against u's new standardised coordinates u' = A⁻¹ (u − m): Cov(x, u) A⁻ᵀ.
  const Eigen::MatrixXd cross_new =
      posterior.topRightCorner(N, 3) * narrowing.transpose().inverse();
  EXPECT_LT((c.cross - cross_new).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((joint_mean.tail(3) - move).cwiseAbs().maxCoeff(), 1e-9);
}

// A track started at a registered radar's fix (its offsets removed by b̂, what b̂ does not know,
// E Σ Eᵀ, in its noise): the error of its position against the bias error's standardised
// coordinates, drawn 4 000 times, is −P₀ Hᵀ R⁻¹ E L (fix_bias_cross), the C̃ it starts with.
TEST(ConsideredBiases, ATrackStartedAtARegisteredFixHoldsItsOffsetsError) {
  using Radar = RangeAzimuthElevation<N>;
  const Radar radar(Vector3(-2000.0, 1000.0, 40.0));
  const Vector3 aircraft(9000.0, 14000.0, 3000.0);
  Covariance<3> r = Covariance<3>::Zero();
  r.diagonal() << 30.0 * 30.0, 0.00087 * 0.00087, 0.0017 * 0.0017;
  // The station's offsets factor E L, as the registration hands it to the start: Σ of
  // [range, azimuth, elevation, clock] from the prior, E taking the offsets, not the clock.
  const PictureSensor<N> sensor = radar;
  const StationBias<N> bias(sensor, SensorBias{40.0, 0.002, 0.001, 0.5});
  const Matrix<3, 4> e_l = bias.offsets_factor(sensor);
  const Vector3 offsets_variance(40.0 * 40.0, 0.002 * 0.002, 0.001 * 0.001);
  EXPECT_TRUE((e_l * e_l.transpose()).isApprox(Matrix3(offsets_variance.asDiagonal()), 1e-12))
      << "E L holds the offsets' covariance E Σ Eᵀ";
  EXPECT_EQ(e_l.col(3).norm(), 0.0) << "a detection's offsets hold none of the clock's error";
  const Covariance<3> noise = r + e_l * e_l.transpose();
  const auto expected_fix = fix_position(1, 0, radar, radar.measure_position(aircraft), noise);
  ASSERT_TRUE(expected_fix.has_value());
  const Matrix<3, 4> expected =
      -expected_fix->covariance * fix_bias_cross(radar, *expected_fix, noise, ConsideredCross(e_l));

  constexpr int kDraws = 4000;
  std::mt19937_64 rng(20261203);
  std::normal_distribution<double> normal;
  Matrix<3, 4> cross = Matrix<3, 4>::Zero();
  Vector3 error_variance = Vector3::Zero();
  for (int draw = 0; draw < kDraws; ++draw) {
    Vector<4> u;
    for (int i = 0; i < 4; ++i) u(i) = normal(rng);
    Vector3 z = radar.measure_position(aircraft) + e_l * u;
    for (int i = 0; i < 3; ++i) z(i) += std::sqrt(r(i, i)) * normal(rng);
    const auto fix = fix_position(1, 0, radar, z, noise);
    ASSERT_TRUE(fix.has_value());
    const Vector3 error = aircraft - fix->position;  // x − x̂
    cross += error * u.transpose();
    error_variance += error.cwiseAbs2();
  }
  cross /= kDraws;
  error_variance /= kDraws;
  for (int i = 0; i < 3; ++i) {
    // Four standard errors of a sample cross-covariance against a unit-variance u.
    const double tolerance = 4.0 * std::sqrt(error_variance(i) / kDraws);
    for (int j = 0; j < 4; ++j) {
      EXPECT_NEAR(cross(i, j), expected(i, j), tolerance) << "entry " << i << ", " << j;
    }
  }
  EXPECT_GT(expected.col(0).norm(), 10.0) << "the range offset's error moves the fix";
}

}  // namespace
}  // namespace skyfuse
