#include "skyfuse/fusion/mixed_stacked_ekf.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "skyfuse/fusion/increment_fusion.hpp"
#include "skyfuse/fusion/information_increment.hpp"
#include "skyfuse/fusion/stacked_ekf.hpp"
#include "skyfuse/registry/registry.hpp"
#include "support/random_problems.hpp"

namespace skyfuse {
namespace {

using Radar = RangeAzimuthElevation<9>;
using Gps = PositionVelocity<9>;
using Pack = AnySensor<9>;
using Mixed = Pack::Observation;

StationObservation<Radar> radar(std::mt19937& rng, int id, const GaussianState<9>& prior) {
  StationObservation<Radar> o;
  o.station_id = id;
  o.sensor = Radar(prior.mean.head<3>() + test::random_vector3(rng, -900.0, 900.0));
  o.noise = Vector3(0.1 * 0.1, 1e-4, 1e-4).asDiagonal();
  o.z = o.sensor.predict(prior.mean) + Vector3(0.05, 0.002, -0.001);
  return o;
}

StationObservation<Gps> gps(std::mt19937& rng, int id, const GaussianState<9>& prior) {
  StationObservation<Gps> o;
  o.station_id = id;
  o.noise = test::random_spd<6>(rng, 1.0, 9.0);
  o.z = o.sensor.predict(prior.mean);
  o.z.head<3>() += test::random_vector3(rng, -3.0, 3.0);
  return o;
}

TEST(MixedStackedEkf, WithOneSensorKindItIsTheStackedEkf) {
  std::mt19937 rng(21);
  for (int trial = 0; trial < 10; ++trial) {
    const GaussianState<9> prior = test::random_prior(rng, Vector3(100.0, -200.0, 400.0));
    std::vector<StationObservation<Radar>> plain;
    std::vector<Mixed> mixed;
    for (int i = 1; i <= 4; ++i) {
      plain.push_back(radar(rng, i, prior));
      mixed.emplace_back(plain.back());
    }
    GaussianState<9> a = prior;
    GaussianState<9> b = prior;
    StackedEkf<9, Radar> fixed_blocks;
    MixedStackedEkf<9, Pack> any;
    const UpdateReport ra = fixed_blocks.update(a, plain);
    const UpdateReport rb = any.update(b, mixed);
    ASSERT_EQ(rb.status, NumericalStatus::kOk);
    EXPECT_LE(test::relative_error(b.mean, a.mean), 1e-12);
    EXPECT_LE(test::relative_error(b.covariance, a.covariance), 1e-9);
    EXPECT_NEAR(rb.nis, ra.nis, 1e-9 * ra.nis);
  }
}

// Radars and a GPS receiver in one stacked update: the same estimate as the information form
// (each one's increment fused into the prior), as for paper 000's stations alone.
TEST(MixedStackedEkf, RadarsAndAGpsEqualTheirFusedIncrements) {
  std::mt19937 rng(22);
  for (int trial = 0; trial < 10; ++trial) {
    const GaussianState<9> prior = test::random_prior(rng, Vector3(-300.0, 200.0, 450.0));
    const StationObservation<Radar> r1 = radar(rng, 1, prior);
    const StationObservation<Radar> r2 = radar(rng, 2, prior);
    const StationObservation<Gps> g = gps(rng, 3, prior);
    const std::vector<Mixed> mixed = {r1, r2, g};

    GaussianState<9> stacked = prior;
    MixedStackedEkf<9, Pack> ekf;
    ASSERT_EQ(ekf.update(stacked, mixed).status, NumericalStatus::kOk);

    std::vector<InformationIncrement<9>> increments(3);
    compute_increment(1, prior, r1.sensor, r1.z, r1.noise, increments[0]);
    compute_increment(2, prior, r2.sensor, r2.z, r2.noise, increments[1]);
    compute_increment(3, prior, g.sensor, g.z, g.noise, increments[2]);
    const std::vector<double> weights(3, 1.0);
    GaussianState<9> fused;
    ASSERT_EQ(fuse_increments<9>(prior, increments, weights, fused), NumericalStatus::kOk);
    EXPECT_LE(test::relative_error(stacked.mean, fused.mean), 1e-9);
    EXPECT_LE(test::relative_error(stacked.covariance, fused.covariance), 1e-7);
  }
}

TEST(MixedStackedEkf, AFailedFactorisationLeavesTheStateAsItWas) {
  std::mt19937 rng(23);
  const GaussianState<9> prior = test::random_prior(rng, Vector3(0.0, 0.0, 400.0));
  StationObservation<Gps> g = gps(rng, 1, prior);
  g.noise = -100.0 * Covariance<6>::Identity();
  const std::vector<Mixed> mixed = {radar(rng, 2, prior), g};
  GaussianState<9> state = prior;
  MixedStackedEkf<9, Pack> ekf;
  EXPECT_EQ(ekf.update(state, mixed).status, NumericalStatus::kNotPositiveDefinite);
  EXPECT_EQ(state.mean, prior.mean);
  EXPECT_EQ(state.covariance, prior.covariance);
}

}  // namespace
}  // namespace skyfuse
