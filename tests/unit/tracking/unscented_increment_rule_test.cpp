// The unscented rule: its NIS gate on P_zz + R, and its reference, the covariance-form UKF on
// the stacked measurement, against the information form the network sums.
#include <gtest/gtest.h>

#include <Eigen/LU>  // inverse(), for the covariance-form reference
#include <random>
#include <vector>

#include "skyfuse/models/position_velocity.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/tracking/unscented_increment_rule_impl.hpp"
#include "support/random_problems.hpp"

namespace skyfuse {
namespace {

using Radar = RangeAzimuthElevation<9>;
using Gps = PositionVelocity<9>;

template <typename Sensor>
StationObservation<Sensor> observe(int id, const Sensor& sensor, const Vector<9>& truth,
                                   const Covariance<Sensor::kMeasDim>& noise,
                                   const Vector<Sensor::kMeasDim>& offset) {
  return {id, sensor, sensor.predict(truth) + offset, noise};
}

// The information form's posterior: the prior's information plus the stations' increments.
GaussianState<9> information_form(const GaussianState<9>& prior,
                                  const std::vector<InformationIncrement<9>>& increments) {
  const Covariance<9> prior_information = prior.covariance.inverse();
  Covariance<9> information = prior_information;
  Vector<9> vector = prior_information * prior.mean;
  for (const auto& d : increments) {
    information += d.delta_information;
    vector += d.delta_vector;
  }
  GaussianState<9> posterior;
  posterior.covariance = information.inverse();
  posterior.mean = posterior.covariance * vector;
  return posterior;
}

// For a linear sensor P_zz = H P H^T: the unscented NIS is the EKF's.
TEST(UnscentedIncrementRule, ALinearSensorsNisIsTheEkfs) {
  std::mt19937 rng(11);
  const Gps gps;
  for (int trial = 0; trial < 20; ++trial) {
    const GaussianState<9> prior = test::random_prior(rng, test::random_vector3(rng, -900, 900));
    const Vector<6> z = prior.mean.head<6>() + Vector<6>::Constant(0.7);
    const Covariance<6> noise = Covariance<6>::Identity() * 0.25;
    SigmaPoints<9> sigma;
    ASSERT_TRUE(sigma.compute(prior, {}));
    const auto unscented = unscented_nis(linearise(sigma, gps, Spread::kForm), gps, z, noise);
    const auto ekf = measurement_nis(prior, gps, z, noise);
    ASSERT_TRUE(unscented && ekf);
    EXPECT_NEAR(*unscented, *ekf, 1e-9 * *ekf) << "trial " << trial;
  }
}

TEST(UnscentedIncrementRule, TheNisGateScreensAnOutlierToAZeroIncrementAndPassesTheRest) {
  std::mt19937 rng(3);
  const GaussianState<9> prior = test::random_prior(rng, Vector3(200.0, -100.0, 400.0));
  const Radar radar(Vector3(-800.0, 100.0, 20.0));
  const Covariance<3> noise = Vector3(0.5 * 0.5, 1e-6, 1e-6).asDiagonal();
  const NisGate gate = NisGate::at_probability(0.9999);
  UnscentedIncrementRule::RoundPrior<9> round_prior;
  ASSERT_TRUE(round_prior.prepare(prior));

  InformationIncrement<9> increment;
  const auto in_line = observe(4, radar, prior.mean, noise, Vector3(0.3, 0.0, 0.0));
  const OwnContribution passed = round_prior.contribute(in_line, gate, increment);
  EXPECT_FALSE(passed.refused);
  EXPECT_EQ(passed.status, NumericalStatus::kOk);
  EXPECT_GT(increment.delta_information.norm(), 0.0);

  const auto outlier = observe(4, radar, prior.mean, noise, Vector3(500.0, 0.0, 0.0));
  const OwnContribution screened = round_prior.contribute(outlier, gate, increment);
  EXPECT_EQ(screened.refused, DropKind::kNisGate);
  EXPECT_EQ(increment.station_id, 4);
  EXPECT_TRUE(increment.delta_information.isZero(0.0));
  EXPECT_TRUE(increment.delta_vector.isZero(0.0));

  // Without a gate the same outlier is fused; the station's own path agrees with the round's.
  EXPECT_FALSE(round_prior.contribute(outlier, NisGate{}, increment).refused);
  InformationIncrement<9> own;
  EXPECT_EQ(UnscentedIncrementRule::contribute(prior, outlier, gate, own).refused,
            DropKind::kNisGate);
}

// Linear sensors: both forms are the Kalman update of the stacked measurement.
TEST(UnscentedIncrementRule, TheCovarianceFormEqualsTheInformationFormForLinearSensors) {
  std::mt19937 rng(19);
  const Gps gps;
  for (int trial = 0; trial < 20; ++trial) {
    const GaussianState<9> prior = test::random_prior(rng, test::random_vector3(rng, -900, 900));
    UnscentedIncrementRule::RoundPrior<9> round_prior;
    ASSERT_TRUE(round_prior.prepare(prior));
    std::vector<StationObservation<Gps>> observations;
    for (int id = 1; id <= 3; ++id) {
      observations.push_back(observe(id, gps, prior.mean, Covariance<6>::Identity() * 0.25 * id,
                                     Vector<6>::Constant(0.2 * id)));
    }
    std::vector<InformationIncrement<9>> increments(observations.size());
    std::vector<const StationObservation<Gps>*> stacked;
    for (std::size_t i = 0; i < observations.size(); ++i) {
      ASSERT_FALSE(round_prior.contribute(observations[i], NisGate{}, increments[i]).refused);
      stacked.push_back(&observations[i]);
    }
    GaussianState<9> reference;
    ASSERT_EQ(round_prior.reference_update(
                  prior, std::span<const StationObservation<Gps>* const>(stacked), reference),
              NumericalStatus::kOk);
    const GaussianState<9> summed = information_form(prior, increments);
    EXPECT_LE(test::relative_error(reference.mean, summed.mean), 1e-9) << "trial " << trial;
    EXPECT_LE(test::relative_error(reference.covariance, summed.covariance), 1e-8)
        << "trial " << trial;
  }
}

// Radars near a wide prior: h curves across the sigma points, and the covariance form, which
// keeps the spread of h about its regression in S, updates less than the information form.
TEST(UnscentedIncrementRule, TheCovarianceFormKeepsTheSpreadTheInformationFormLeavesOut) {
  GaussianState<9> prior;
  prior.mean << 60.0, 40.0, 80.0, 10.0, 0.0, 0.0, 0.0, 0.0, 0.0;
  prior.covariance = Covariance<9>::Identity() * 400.0;
  UnscentedIncrementRule::RoundPrior<9> round_prior;
  ASSERT_TRUE(round_prior.prepare(prior));
  const Covariance<3> noise = Vector3(0.5 * 0.5, 1e-4, 1e-4).asDiagonal();
  const std::vector<StationObservation<Radar>> observations = {
      observe(1, Radar(Vector3(0.0, 0.0, 20.0)), prior.mean, noise, Vector3(1.0, 0.0, 0.0)),
      observe(2, Radar(Vector3(150.0, -50.0, 10.0)), prior.mean, noise, Vector3(-1.0, 0.0, 0.0))};
  std::vector<InformationIncrement<9>> increments(observations.size());
  std::vector<const StationObservation<Radar>*> stacked;
  for (std::size_t i = 0; i < observations.size(); ++i) {
    ASSERT_FALSE(round_prior.contribute(observations[i], NisGate{}, increments[i]).refused);
    stacked.push_back(&observations[i]);
  }
  GaussianState<9> reference;
  ASSERT_EQ(round_prior.reference_update(
                prior, std::span<const StationObservation<Radar>* const>(stacked), reference),
            NumericalStatus::kOk);
  const GaussianState<9> summed = information_form(prior, increments);
  const auto position_variance = [](const GaussianState<9>& s) {
    return s.covariance.topLeftCorner<3, 3>().trace();
  };
  EXPECT_GT((reference.mean - summed.mean).norm(), 1e-6);
  EXPECT_GT(position_variance(reference), position_variance(summed));
  // Both still update: well inside the prior.
  EXPECT_LT(position_variance(reference), position_variance(prior));
}

TEST(UnscentedIncrementRule, TheCovarianceFormOfNoMeasurementIsThePrior) {
  std::mt19937 rng(2);
  const GaussianState<9> prior = test::random_prior(rng, Vector3(0.0, 0.0, 300.0));
  UnscentedIncrementRule::RoundPrior<9> round_prior;
  ASSERT_TRUE(round_prior.prepare(prior));
  GaussianState<9> reference;
  ASSERT_EQ(round_prior.reference_update(prior, std::span<const StationObservation<Radar>* const>{},
                                         reference),
            NumericalStatus::kOk);
  EXPECT_EQ(reference.mean, prior.mean);
  EXPECT_EQ(reference.covariance, prior.covariance);
}

}  // namespace
}  // namespace skyfuse
