#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <array>
#include <cstdio>
#include <random>

#include "skyfuse/fusion/increment_fusion.hpp"
#include "skyfuse/fusion/information_increment.hpp"
#include "skyfuse/fusion/relinearised_increment_impl.hpp"
#include "skyfuse/metrics/chi_square.hpp"
#include "skyfuse/models/position_sensor.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"

namespace skyfuse {
namespace {

using Radar = RangeAzimuthElevation<6>;

// A radar 60 m up at the origin, noise 30 m, 0.05 deg, 0.1 deg; an aircraft 6 km from it at
// 2.4 km height (the geometry in which a fresh track's EKF update comes out biased).
const Vector3 kSite(0.0, 0.0, 60.0);
const Vector3 kAircraft(-1100.0, 5400.0, 2400.0);

Covariance<3> radar_noise() {
  Covariance<3> r = Covariance<3>::Zero();
  r.diagonal() << 30.0 * 30.0, 0.00087 * 0.00087, 0.0017 * 0.0017;
  return r;
}

// A fresh track's prior: 600 m per axis in position (its velocity a guess, 4 s old), 100 m/s.
GaussianState<6> broad_prior(const Vector<6>& mean) {
  GaussianState<6> prior;
  prior.mean = mean;
  prior.covariance = Covariance<6>::Zero();
  prior.covariance.diagonal() << 600.0 * 600.0, 600.0 * 600.0, 600.0 * 600.0, 1e4, 1e4, 1e4;
  return prior;
}

// The posterior of one detection whose increment was linearised after `times` steps.
GaussianState<6> posterior_of(const GaussianState<6>& prior, const StationObservation<Radar>& o,
                              int times) {
  InformationIncrement<6> increment;
  EXPECT_EQ(compute_increment(o.station_id, relinearised_prior(prior, o, times), o.sensor, o.z,
                              o.noise, increment),
            NumericalStatus::kOk);
  GaussianState<6> posterior;
  const std::array<double, 1> weight = {1.0};
  EXPECT_EQ(fuse_increments(prior, std::span<const InformationIncrement<6>>(&increment, 1), weight,
                            posterior),
            NumericalStatus::kOk);
  return posterior;
}

// The gradient of the MAP cost (x - x⁻)ᵀ P⁻¹ (x - x⁻) + ν(x)ᵀ R⁻¹ ν(x), halved: zero at the
// posterior mode, which the iterated EKF's steps approach.
Vector<6> map_gradient(const GaussianState<6>& prior, const StationObservation<Radar>& o,
                       const Vector<6>& x) {
  const Eigen::LLT<Eigen::Matrix<double, 6, 6>> p(prior.covariance);
  const Eigen::LLT<Eigen::Matrix3d> r(o.noise);
  const Vector3 nu = Radar::residual(o.z, o.sensor.predict(x));
  return p.solve(x - prior.mean) - o.sensor.jacobian(x).transpose() * r.solve(nu);
}

TEST(RelinearisedIncrement, NoStepLinearisesAtThePrior) {
  const GaussianState<6> prior = broad_prior((Vector<6>() << kAircraft, 100, 0, 0).finished());
  const Radar radar(kSite);
  const StationObservation<Radar> o{3, radar, radar.measure_position(kAircraft + Vector3(5, 0, 0)),
                                    radar_noise()};
  const GaussianState<6> at = relinearised_prior(prior, o, 0);
  EXPECT_EQ(at.mean, prior.mean);
  EXPECT_EQ(at.covariance, prior.covariance);
}

TEST(RelinearisedIncrement, StepsApproachThePosteriorMode) {
  // The prior 600 m behind the aircraft: the EKF's posterior is far from the mode (the MAP
  // estimate), and each step brings it closer.
  Vector<6> mean;
  mean << kAircraft + Vector3(560.0, -180.0, 0.0), 0.0, 0.0, 0.0;
  const GaussianState<6> prior = broad_prior(mean);
  const Radar radar(kSite);
  const StationObservation<Radar> o{3, radar, radar.measure_position(kAircraft), radar_noise()};

  // The posterior's distance to the mode (four steps' posterior) and the MAP cost's gradient
  // each fall tenfold or more with every step.
  const Vector<6> mode = posterior_of(prior, o, 4).mean;
  double last_gradient = 0.0;
  double last_distance = 0.0;
  for (int times = 0; times <= 3; ++times) {
    const Vector<6> x = posterior_of(prior, o, times).mean;
    const double gradient = map_gradient(prior, o, x).norm();
    const double distance = (x - mode).head<3>().norm();
    std::printf("%d steps: %.4g m from the mode, gradient %.3g\n", times, distance, gradient);
    if (times > 0) {
      EXPECT_LT(gradient, 0.1 * last_gradient) << times << " steps";
      EXPECT_LT(distance, 0.1 * last_distance) << times << " steps";
    }
    last_gradient = gradient;
    last_distance = distance;
  }
  EXPECT_GT((posterior_of(prior, o, 0).mean - mode).head<3>().norm(), 10.0)
      << "the geometry linearises badly at the prior";
  EXPECT_LT(map_gradient(prior, o, mode).norm(), 1e-6);
}

TEST(RelinearisedIncrement, ALinearSensorGivesTheSameIncrement) {
  using Position = PositionSensor<6>;
  Vector<6> mean;
  mean << 100.0, -250.0, 900.0, 10.0, 0.0, 0.0;
  const GaussianState<6> prior = broad_prior(mean);
  const StationObservation<Position> o{2, Position{}, Vector3(140.0, -300.0, 880.0),
                                       Covariance<3>(Covariance<3>::Identity() * 25.0)};
  InformationIncrement<6> plain;
  InformationIncrement<6> relinearised;
  ASSERT_EQ(compute_increment(2, prior, o.sensor, o.z, o.noise, plain), NumericalStatus::kOk);
  ASSERT_EQ(
      compute_increment(2, relinearised_prior(prior, o, 3), o.sensor, o.z, o.noise, relinearised),
      NumericalStatus::kOk);
  EXPECT_EQ(relinearised.delta_information, plain.delta_information);
  EXPECT_LT((relinearised.delta_vector - plain.delta_vector).norm(),
            1e-12 * plain.delta_vector.norm());
}

// A Monte Carlo of the fresh track's update near the radar: priors drawn from N(x, P), the
// detection from N(h(x), R). Linearised at the prior, the posterior's position error is many
// times its covariance; relinearised twice, its ANEES is inside the chi-square band.
TEST(RelinearisedIncrement, AFreshTracksUpdateNearARadarIsConsistentRelinearised) {
  constexpr int kDraws = 2000;
  constexpr double kDof = 3.0;
  std::mt19937_64 rng(20261201);
  std::normal_distribution<double> normal;
  const Radar radar(kSite);
  const Covariance<3> r = radar_noise();
  Vector<6> truth;
  truth << kAircraft, -140.0, 44.0, 0.0;
  const Eigen::Matrix<double, 6, 6> prior_factor =
      broad_prior(truth).covariance.llt().matrixL().toDenseMatrix();

  std::array<double, 3> nees_sum{};  // 0, 1 and 2 steps
  for (int draw = 0; draw < kDraws; ++draw) {
    Vector<6> n;
    for (int i = 0; i < 6; ++i) n(i) = normal(rng);
    const GaussianState<6> prior = broad_prior(truth + prior_factor * n);
    Vector3 z = radar.measure_position(truth.head<3>());
    for (int i = 0; i < 3; ++i) z(i) += std::sqrt(r(i, i)) * normal(rng);
    const StationObservation<Radar> o{1, radar, z, r};
    for (int times = 0; times <= 2; ++times) {
      const GaussianState<6> posterior = posterior_of(prior, o, times);
      const Vector3 error = posterior.mean.head<3>() - truth.head<3>();
      nees_sum[static_cast<std::size_t>(times)] +=
          error.dot(posterior.covariance.topLeftCorner<3, 3>().llt().solve(error));
    }
  }
  // The 0.999 band of the mean NEES per dof over kDraws independent samples.
  const double samples = kDraws * kDof;
  const double low = chi_square_quantile(0.0005, samples) / samples;
  const double high = chi_square_quantile(0.9995, samples) / samples;
  const double at_prior = nees_sum[0] / samples;
  const double once = nees_sum[1] / samples;
  const double twice = nees_sum[2] / samples;
  std::printf(
      "ANEES per dof: at the prior %.3f, relinearised once %.3f, twice %.3f; "
      "band [%.3f, %.3f]\n",
      at_prior, once, twice, low, high);
  // Linearised at the prior it is far outside; once, most of the way in (the prior is 600 m
  // wide at 6 km: the first step's point is still tens of metres off); twice, inside.
  EXPECT_GT(at_prior, 10.0 * high);
  EXPECT_LT(once - 1.0, 0.1 * (at_prior - 1.0));
  EXPECT_GE(twice, low);
  EXPECT_LE(twice, high);
}

}  // namespace
}  // namespace skyfuse
