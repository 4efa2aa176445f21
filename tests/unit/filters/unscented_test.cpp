// The unscented information filter's measurement step: its sigma points, its statistical
// linearisation, and its increment against the EKF's.
#include "skyfuse/filters/unscented.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include "skyfuse/models/position_velocity.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "support/random_problems.hpp"

namespace skyfuse {
namespace {

TEST(SigmaPoints, CarryThePriorsMeanAndCovariance) {
  std::mt19937 rng(5);
  const GaussianState<9> prior = test::random_prior(rng, Vector3(300.0, -200.0, 450.0));
  for (const UnscentedParameters p : {UnscentedParameters{}, UnscentedParameters{1e-3, 2.0, 0.0},
                                      UnscentedParameters{0.5, 2.0, 1.0}}) {
    SigmaPoints<9> sigma;
    ASSERT_TRUE(sigma.compute(prior, p));
    Vector<9> mean = Vector<9>::Zero();
    double weights = 0.0;
    for (int j = 0; j < SigmaPoints<9>::kCount; ++j) {
      mean += sigma.mean_weight(j) * sigma.point(j);
      weights += sigma.mean_weight(j);
    }
    Covariance<9> covariance = Covariance<9>::Zero();
    for (int j = 0; j < SigmaPoints<9>::kCount; ++j) {
      covariance += sigma.covariance_weight(j) * (sigma.point(j) - prior.mean) *
                    (sigma.point(j) - prior.mean).transpose();
    }
    // The centre weight's extra (1 - alpha^2 + beta) multiplies a zero deviation. With
    // alpha = 1e-3 the centre weight is about -1e6 and the others +1e6 in all: the mean cancels
    // six digits (2e-10 relative, measured).
    EXPECT_NEAR(weights, 1.0, 1e-9) << "alpha " << p.alpha;
    EXPECT_LE(test::relative_error(mean, prior.mean), 1e-9) << "alpha " << p.alpha;
    EXPECT_LE(test::relative_error(covariance, prior.covariance), 1e-9) << "alpha " << p.alpha;
  }
}

TEST(SigmaPoints, RefuseACovarianceThatIsNotPositiveDefinite) {
  GaussianState<9> prior;
  prior.covariance(4, 4) = -1.0;
  SigmaPoints<9> sigma;
  EXPECT_FALSE(sigma.compute(prior, {}));
}

// For a linear sensor the regression is the sensor's matrix, and the increment the EKF's.
TEST(UnscentedIncrement, EqualsTheEkfsForALinearSensor) {
  std::mt19937 rng(7);
  const PositionVelocity<9> gps;
  for (int trial = 0; trial < 50; ++trial) {
    const GaussianState<9> prior = test::random_prior(rng, test::random_vector3(rng, -900, 900));
    const Vector<6> z = prior.mean.head<6>() + Vector<6>::Constant(0.3);
    const Covariance<6> noise = Covariance<6>::Identity() * 0.25;
    SigmaPoints<9> sigma;
    ASSERT_TRUE(sigma.compute(prior, {}));
    InformationIncrement<9> unscented;
    InformationIncrement<9> ekf;
    ASSERT_EQ(compute_unscented_increment(3, sigma, gps, z, noise, unscented),
              NumericalStatus::kOk);
    ASSERT_EQ(compute_increment(3, prior, gps, z, noise, ekf), NumericalStatus::kOk);
    EXPECT_EQ(unscented.station_id, 3);
    EXPECT_LE(test::relative_error(unscented.delta_information, ekf.delta_information), 1e-9)
        << "trial " << trial;
    EXPECT_LE(test::relative_error(unscented.delta_vector, ekf.delta_vector), 1e-9)
        << "trial " << trial;
  }
}

// A radar's h is curved: spread sigma points regress on a chord, not the tangent. As they
// close in on the mean (alpha -> 0) the regression becomes the Jacobian and the increment the
// EKF's; spread at sqrt(N) standard deviations of a wide prior near the radar, it differs.
TEST(UnscentedIncrement, ApproachesTheEkfsAsTheSigmaPointsCloseIn) {
  const RangeAzimuthElevation<9> radar(Vector3(0.0, 0.0, 20.0));
  GaussianState<9> prior;
  prior.mean.head<3>() = Vector3(60.0, 40.0, 80.0);
  prior.covariance.topLeftCorner<3, 3>() *= 100.0;  // 10 m in each axis, 100 m from the radar
  const Vector3 z = radar.predict(prior.mean) + Vector3(0.5, 0.01, -0.01);
  Covariance<3> noise = Covariance<3>::Zero();
  noise.diagonal() << 0.1 * 0.1, 0.01 * 0.01, 0.01 * 0.01;
  InformationIncrement<9> ekf;
  ASSERT_EQ(compute_increment(1, prior, radar, z, noise, ekf), NumericalStatus::kOk);
  const auto difference = [&](double alpha) {
    SigmaPoints<9> sigma;
    EXPECT_TRUE(sigma.compute(prior, {alpha, 2.0, 0.0}));
    InformationIncrement<9> unscented;
    EXPECT_EQ(compute_unscented_increment(1, sigma, radar, z, noise, unscented),
              NumericalStatus::kOk);
    return test::relative_error(unscented.delta_information, ekf.delta_information);
  };
  const double wide = difference(1.0);
  const double close = difference(1e-3);
  EXPECT_GT(wide, 1e-3);
  EXPECT_LT(close, 1e-5);
  EXPECT_LT(close, wide * 1e-2);
}

// Azimuths of sigma points on both sides of the -x axis average near +-pi, not near 0.
TEST(UnscentedIncrement, PredictsAnAzimuthAcrossPiWhereItLies) {
  const RangeAzimuthElevation<9> radar(Vector3::Zero());
  GaussianState<9> prior;
  prior.mean.head<3>() = Vector3(-500.0, 0.0, 100.0);  // azimuth pi
  prior.covariance.topLeftCorner<3, 3>() *= 400.0;     // 20 m: points at either sign of y
  SigmaPoints<9> sigma;
  ASSERT_TRUE(sigma.compute(prior, {}));
  const auto lin = linearise(sigma, radar);
  EXPECT_NEAR(std::abs(lin.predicted(1)), std::numbers::pi, 1e-3);
}

}  // namespace
}  // namespace skyfuse
