#include "skyfuse/fusion/information_increment.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>  // the paper's form needs explicit inverses; the code under test does not
#include <random>

#include "skyfuse/filters/kalman.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "support/random_problems.hpp"

namespace skyfuse {
namespace {

using Sensor = RangeAzimuthElevation<9>;

// The paper's form: run the local EKF update, then difference the information matrices and
// vectors, dQ = (P+)^-1 - (P-)^-1, dy = (P+)^-1 x+ - (P-)^-1 x-.
InformationIncrement<9> paper_inversion_form(const GaussianState<9>& prior, const Sensor& sensor,
                                             const Vector3& z, const Covariance<3>& noise) {
  GaussianState<9> posterior = prior;
  EXPECT_EQ(update(posterior, sensor, z, noise).status, NumericalStatus::kOk);
  const Covariance<9> prior_info = prior.covariance.inverse();
  const Covariance<9> posterior_info = posterior.covariance.inverse();
  InformationIncrement<9> inc;
  inc.delta_information = posterior_info - prior_info;
  inc.delta_vector = posterior_info * posterior.mean - prior_info * prior.mean;
  return inc;
}

TEST(InformationIncrement, DirectFormEqualsThePapersInversionForm) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 200; ++trial) {
    const Vector3 target = test::random_vector3(rng, -1500.0, 1500.0) + Vector3(0, 0, 1600.0);
    const GaussianState<9> prior = test::random_prior(rng, target);
    const Sensor sensor(test::random_vector3(rng, -1500.0, 1500.0));
    const Vector3 z = sensor.measure_position(target);
    Covariance<3> noise = Covariance<3>::Zero();
    noise.diagonal() << 0.1 * 0.1, 0.01 * 0.01, 0.01 * 0.01;
    noise *= std::uniform_real_distribution<double>(0.1, 3.0)(rng);

    InformationIncrement<9> direct;
    ASSERT_EQ(compute_increment(4, prior, sensor, z, noise, direct), NumericalStatus::kOk);
    const InformationIncrement<9> paper = paper_inversion_form(prior, sensor, z, noise);

    EXPECT_EQ(direct.station_id, 4);
    // The inversion form loses digits to the conditioning of P; 1e-6 leaves room for that.
    EXPECT_LE(test::relative_error(direct.delta_information, paper.delta_information), 1e-6)
        << "trial " << trial;
    EXPECT_LE(test::relative_error(direct.delta_vector, paper.delta_vector), 1e-6)
        << "trial " << trial;
    EXPECT_TRUE(direct.delta_information.isApprox(direct.delta_information.transpose(), 0.0));
  }
}

TEST(InformationIncrement, OnlyThePositionBlockCarriesInformation) {
  std::mt19937 rng(3);
  const GaussianState<9> prior = test::random_prior(rng, Vector3(400.0, 300.0, 450.0));
  const Sensor sensor(Vector3(0.0, 0.0, 20.0));
  InformationIncrement<9> inc;
  ASSERT_EQ(compute_increment(1, prior, sensor, Vector3(640.0, 0.64, 0.6),
                              Covariance<3>::Identity(), inc),
            NumericalStatus::kOk);
  EXPECT_GT((inc.delta_information.topLeftCorner<3, 3>().norm()), 0.0);
  EXPECT_EQ(inc.delta_information.bottomRows<6>().norm(), 0.0);
  EXPECT_EQ(inc.delta_information.rightCols<6>().norm(), 0.0);
  EXPECT_EQ(inc.delta_vector.tail<6>().norm(), 0.0);
}

TEST(InformationIncrement, RefusesANoiseCovarianceThatIsNotPositiveDefinite) {
  const GaussianState<9> prior;
  const Sensor sensor(Vector3(0.0, 0.0, 0.0));
  Covariance<3> noise = Covariance<3>::Identity();
  noise(1, 1) = 0.0;
  InformationIncrement<9> inc;
  EXPECT_EQ(compute_increment(1, prior, sensor, Vector3(1.0, 0.0, 0.0), noise, inc),
            NumericalStatus::kNotPositiveDefinite);
}

}  // namespace
}  // namespace skyfuse
