// Consistency of the filter on a linear-Gaussian case, where the truth follows the filter's own
// model exactly: NEES must then be chi^2(9), and ANEES over N runs inside its 95 % band.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "skyfuse/filters/kalman.hpp"
#include "skyfuse/metrics/chi_square.hpp"
#include "skyfuse/metrics/nees.hpp"
#include "skyfuse/models/constant_acceleration.hpp"
#include "skyfuse/models/position_sensor.hpp"
#include "skyfuse/random/counter_rng.hpp"
#include "support/draw_last_first.hpp"

namespace skyfuse {
namespace {

constexpr int kRuns = 100;
constexpr int kSteps = 150;

struct ConsistencyResult {
  double time_averaged_anees = 0.0;
  double fraction_of_steps_in_band = 0.0;
  ChiSquareBand band;
};

Vector<9> draw(CounterRng& rng, const Covariance<9>& cov) {
  const Eigen::LLT<Covariance<9>> factor(cov);
  Vector<9> n;
  for (int i = 0; i < 9; ++i) n(i) = rng.normal();
  return factor.matrixL() * n;
}

// Truth from (q_truth), filter told q_filter; position measured with std 2 m.
ConsistencyResult run_linear_gaussian(const ConstantAcceleration3D::NoiseStd& q_truth,
                                      const ConstantAcceleration3D::NoiseStd& q_filter) {
  const ConstantAcceleration3D truth_model(0.1, q_truth);
  const ConstantAcceleration3D filter_model(0.1, q_filter);
  const PositionSensor<9> sensor;
  const Covariance<3> noise = 4.0 * Covariance<3>::Identity();
  const Covariance<9> p0 = Vector<9>(Vector<9>::Constant(1.0)).asDiagonal();

  std::vector<double> nees_sum(kSteps, 0.0);
  for (std::uint64_t run = 0; run < kRuns; ++run) {
    CounterRng init_rng({42, run, 0, 0, NoiseStream::kInitialState});
    Vector<9> x = Vector<9>::Zero();
    x.segment<3>(3) = Vector3(20.0, -5.0, 1.0);
    GaussianState<9> estimate{x + draw(init_rng, p0), p0};
    for (int k = 0; k < kSteps; ++k) {
      CounterRng rng({42, run, 1, static_cast<std::uint64_t>(k), NoiseStream::kMeasurement});
      const Vector3 z = x.head<3>() + 2.0 * test::draw_last_first<3>([&] { return rng.normal(); });
      EXPECT_EQ(update(estimate, sensor, z, noise).status, NumericalStatus::kOk);
      nees_sum[static_cast<std::size_t>(k)] += nees(x, estimate);

      CounterRng process_rng({42, run, 0, static_cast<std::uint64_t>(k), NoiseStream::kProcess});
      x = truth_model.propagate(x) + draw(process_rng, truth_model.process_noise());
      predict(estimate, filter_model);
    }
  }

  ConsistencyResult result;
  result.band = average_chi_square_band(9, kRuns);
  int in_band = 0;
  for (double sum : nees_sum) {
    const double anees = sum / kRuns;
    result.time_averaged_anees += anees / kSteps;
    if (result.band.contains(anees)) ++in_band;
  }
  result.fraction_of_steps_in_band = static_cast<double>(in_band) / kSteps;
  return result;
}

TEST(KalmanFilter, AneesLiesInsideIts95PercentBandOnALinearGaussianCase) {
  const ConstantAcceleration3D::NoiseStd q{0.05, 0.2, 0.5};
  const ConsistencyResult r = run_linear_gaussian(q, q);
  EXPECT_TRUE(r.band.contains(r.time_averaged_anees))
      << "ANEES " << r.time_averaged_anees << " outside [" << r.band.lower << ", " << r.band.upper
      << "]";
  // Per step, 95 % of ANEES values should fall in the band; allow for sampling spread.
  EXPECT_GE(r.fraction_of_steps_in_band, 0.88);
}

TEST(KalmanFilter, AneesLeavesTheBandWhenTheFilterUnderstatesProcessNoise) {
  // The same test must be able to fail: a filter that believes Q is 100x smaller than it is
  // becomes overconfident and its ANEES rises above the band.
  const ConsistencyResult r = run_linear_gaussian({0.05, 0.2, 0.5}, {0.005, 0.02, 0.05});
  EXPECT_GT(r.time_averaged_anees, r.band.upper);
}

// The Joseph form is right for any gain, not only the optimal one: the structured product
// (which skips the identity and zero parts of I - KH) against the plain dense formula, with a
// gain half the optimal one, where the short form (I - KH) P is wrong.
TEST(KalmanFilter, JosephCovarianceIsTheDenseFormulaForAnyGain) {
  Matrix<9, 9> a = Matrix<9, 9>::Random();
  const Covariance<9> p = a * a.transpose() + Covariance<9>::Identity();
  Matrix<3, 9> h = Matrix<3, 9>::Zero();
  h.leftCols<3>() = Matrix<3, 3>::Random();
  const Covariance<3> r = Vector3(0.5, 0.2, 0.1).asDiagonal();
  const Covariance<3> s = h * p * h.transpose() + r;
  const Matrix<9, 3> gain = 0.5 * s.llt().solve(h * p).transpose();  // S, P symmetric

  const Matrix<9, 3> kh = gain * h.leftCols<3>();
  const Covariance<9> structured = joseph_covariance<9, 3, 3>(p, kh, gain, r);
  const Covariance<9> i_kh = Covariance<9>::Identity() - gain * h;
  const Covariance<9> dense = i_kh * p * i_kh.transpose() + gain * r * gain.transpose();
  EXPECT_LT((structured - dense).norm(), 1e-12 * dense.norm());
  EXPECT_GT((i_kh * p - dense).norm(), 1e-3 * dense.norm()) << "the short form would do too";
}

// A thousand updates in a row leave the covariance positive definite.
TEST(KalmanFilter, RepeatedUpdatesKeepTheCovariancePositiveDefinite) {
  GaussianState<9> state;
  state.covariance.setIdentity();
  const ConstantAcceleration3D model(0.02, {0.5, 0.1, 0.05});
  const PositionSensor<9> sensor;
  for (int k = 0; k < 1000; ++k) {
    predict(state, model);
    ASSERT_EQ(
        update(state, sensor, Vector3(1.0, 2.0, 3.0), 0.01 * Covariance<3>::Identity()).status,
        NumericalStatus::kOk);
  }
  EXPECT_EQ(Eigen::LLT<Covariance<9>>(state.covariance).info(), Eigen::Success);
}

TEST(KalmanFilter, UpdateReportsANonPositiveInnovationCovarianceAndLeavesTheState) {
  GaussianState<9> state;
  state.covariance.setZero();
  const GaussianState<9> before = state;
  const PositionSensor<9> sensor;
  const UpdateReport report = update(state, sensor, Vector3(1.0, 2.0, 3.0), Covariance<3>::Zero());
  EXPECT_EQ(report.status, NumericalStatus::kNotPositiveDefinite);
  EXPECT_TRUE(std::isnan(report.nis));
  EXPECT_EQ(state.mean, before.mean);
}

// A NaN in the innovation covariance is a failure, not a NaN state reported as kOk.
TEST(KalmanFilter, UpdateReportsANaNInnovationCovarianceAndLeavesTheState) {
  GaussianState<9> state;
  state.covariance.setIdentity();
  state.covariance(1, 1) = std::nan("");
  const GaussianState<9> before = state;
  const PositionSensor<9> sensor;
  const UpdateReport report =
      update(state, sensor, Vector3(1.0, 2.0, 3.0), 0.01 * Covariance<3>::Identity());
  EXPECT_EQ(report.status, NumericalStatus::kNotPositiveDefinite);
  EXPECT_EQ(state.mean, before.mean);
}

}  // namespace
}  // namespace skyfuse
