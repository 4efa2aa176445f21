// Paper 000's central claim: with w_i = 1, fusing the stations' information increments gives
// the same estimate as one EKF update with every measurement stacked.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "skyfuse/fusion/increment_fusion.hpp"
#include "skyfuse/fusion/stacked_ekf.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "support/random_problems.hpp"

namespace skyfuse {
namespace {

using Sensor = RangeAzimuthElevation<9>;

struct Problem {
  GaussianState<9> prior;
  std::vector<StationObservation<Sensor>> observations;
};

Problem random_problem(std::mt19937& rng, int stations) {
  Problem p;
  const Vector3 target = test::random_vector3(rng, -1000.0, 1000.0) + Vector3(0, 0, 1500.0);
  p.prior = test::random_prior(rng, target);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int i = 0; i < stations; ++i) {
    StationObservation<Sensor> obs;
    obs.station_id = 10 + 3 * i;
    obs.sensor = Sensor(test::random_vector3(rng, -2000.0, 2000.0));
    obs.noise = test::random_spd<3>(rng, 1e-4, 1e-2);
    obs.z = Sensor::residual(
        obs.sensor.measure_position(target) +
            Vector3(0.1, 0.01, 0.01).cwiseProduct(test::draw_last_first<3>([&] { return n(rng); })),
        Vector3::Zero());
    p.observations.push_back(obs);
  }
  return p;
}

GaussianState<9> fuse_with_weights(const Problem& p, const std::vector<double>& weights) {
  std::vector<InformationIncrement<9>> increments(p.observations.size());
  for (std::size_t i = 0; i < p.observations.size(); ++i) {
    const auto& obs = p.observations[i];
    EXPECT_EQ(
        compute_increment(obs.station_id, p.prior, obs.sensor, obs.z, obs.noise, increments[i]),
        NumericalStatus::kOk);
  }
  GaussianState<9> fused;
  EXPECT_EQ(fuse_increments<9>(p.prior, increments, weights, fused), NumericalStatus::kOk);
  return fused;
}

TEST(IncrementFusion, EqualsTheStackedEkfWithUnitWeights) {
  std::mt19937 rng(2025);
  StackedEkf<9, Sensor> stacked;
  for (int trial = 0; trial < 300; ++trial) {
    const int m = std::uniform_int_distribution<int>(1, 16)(rng);
    const Problem p = random_problem(rng, m);

    const GaussianState<9> fused = fuse_with_weights(p, std::vector<double>(m, 1.0));
    GaussianState<9> central = p.prior;
    ASSERT_EQ(stacked.update(central, p.observations).status, NumericalStatus::kOk);

    // Positions are ~1e3 m, so 1e-8 m is ~1e-11 relative: agreement to rounding.
    EXPECT_LE((fused.mean.head<3>() - central.mean.head<3>()).norm(), 1e-8)
        << "trial " << trial << ", M = " << m;
    EXPECT_LE(test::relative_error(fused.mean, central.mean), 1e-9) << "trial " << trial;
    EXPECT_LE(test::relative_error(fused.covariance, central.covariance), 1e-8)
        << "trial " << trial;
  }
}

TEST(IncrementFusion, WeightTwoCountsAsHalfTheNoise) {
  // w_i dQ_i with w_i = 2 is the information of a measurement with noise R_i / 2.
  std::mt19937 rng(5);
  Problem p = random_problem(rng, 3);
  const GaussianState<9> weighted = fuse_with_weights(p, {2.0, 1.0, 2.0});
  p.observations[0].noise /= 2.0;
  p.observations[2].noise /= 2.0;
  const GaussianState<9> halved = fuse_with_weights(p, {1.0, 1.0, 1.0});
  EXPECT_LE(test::relative_error(weighted.mean, halved.mean), 1e-12);
  EXPECT_LE(test::relative_error(weighted.covariance, halved.covariance), 1e-10);
}

TEST(IncrementFusion, RefusesIncrementsOutOfStationOrder) {
  std::mt19937 rng(9);
  const Problem p = random_problem(rng, 2);
  std::vector<InformationIncrement<9>> increments(2);
  increments[0].station_id = 5;
  increments[1].station_id = 4;
  const std::vector<double> weights{1.0, 1.0};
  GaussianState<9> out = p.prior;
  EXPECT_EQ(fuse_increments<9>(p.prior, increments, weights, out),
            NumericalStatus::kIncrementsOutOfOrder);
  EXPECT_EQ(out.mean, p.prior.mean);
}

TEST(IncrementFusion, ReportsAPriorThatIsNotPositiveDefinite) {
  GaussianState<9> prior;
  prior.covariance(4, 4) = -1.0;
  GaussianState<9> out;
  EXPECT_EQ(fuse_increments<9>(prior, std::span<const InformationIncrement<9>>{}, {}, out),
            NumericalStatus::kNotPositiveDefinite);
}

}  // namespace
}  // namespace skyfuse
