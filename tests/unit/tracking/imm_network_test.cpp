// The station network's IMM: peers fusing per-mode increments with the likelihood terms equal
// the central stacked IMM, and the IMM follows paper 000's turn where the CA filter lags.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "skyfuse/experiments/network_imm.hpp"
#include "skyfuse/fusion/fused_likelihood.hpp"
#include "skyfuse/fusion/stacked_likelihood.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"

namespace skyfuse {
namespace {

constexpr double k300KmhInMps = 300.0 / 3.6;

TEST(FusedLikelihood, EqualsTheStackedLikelihoodOfTheSameMeasurements) {
  GaussianState<9> prior;
  prior.mean << 100.0, -50.0, 400.0, 80.0, 10.0, 0.0, 0.1, 0.0, 0.0;
  prior.covariance = Covariance<9>::Identity();
  prior.covariance(0, 3) = prior.covariance(3, 0) = 0.3;
  const Vector3 sites[] = {{0.0, 0.0, 20.0}, {900.0, 300.0, 40.0}, {-500.0, 800.0, 10.0}};
  std::vector<StationObservation<RangeAzimuthElevation<9>>> observations;
  std::vector<InformationIncrement<9>> increments(3);
  std::vector<LikelihoodTerms> terms(3);
  for (int i = 0; i < 3; ++i) {
    const RangeAzimuthElevation<9> radar(sites[i]);
    const Vector3 z = radar.predict(prior.mean) + Vector3(1.5 - i, 0.02, -0.01 * i);
    const Covariance<3> r = Vector3(0.1 * (i + 1), 1e-4, 2e-4).asDiagonal();
    observations.push_back({i + 1, radar, z, r});
    ASSERT_EQ(compute_increment(i + 1, prior, radar, z, r, increments[i], terms[i]),
              NumericalStatus::kOk);
  }
  GaussianState<9> stacked = prior;
  const UpdateReport central = stacked_update_with_likelihood(stacked, observations);
  GaussianState<9> fused;
  int dim = 0;
  const std::vector<double> weights(3, 1.0);
  const UpdateReport peers = fuse_increments_with_likelihood(
      prior, std::span<const InformationIncrement<9>>(increments), terms, weights, fused, dim);
  ASSERT_EQ(dim, 9);
  EXPECT_NEAR(peers.nis, central.nis, 1e-9 * central.nis);
  EXPECT_NEAR(peers.log_det_innovation, central.log_det_innovation, 1e-9);
  EXPECT_NEAR(peers.log_likelihood(dim), central.log_likelihood(9), 1e-8);
  EXPECT_LT((fused.mean - stacked.mean).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(NetworkImm, PeersEqualTheCentralStackedImmAndEachOtherOnPaper000) {
  const Scenario scenario = load_default_scenario();
  const CentralPeerComparison c =
      compare_central_and_peers(scenario, ImmModes{}, k300KmhInMps, 4, 0, scenario.steps);
  EXPECT_EQ(c.steps, 2000);
  EXPECT_TRUE(c.peers_identical);
  EXPECT_LT(c.max_position_difference_m, 1e-9);
  EXPECT_LT(c.max_probability_difference, 1e-9);
  EXPECT_NEAR(c.final_probabilities.sum(), 1.0, 1e-12);
}

TEST(NetworkImm, FollowsTheTurnWhereTheCaFilterLags) {
  const Scenario scenario = load_default_scenario();
  const TurnComparison t = imm_against_ca(scenario, ImmModes{}, k300KmhInMps, 4, 5);
  // The turn runs from 10 s to 18 s: the CT mode takes over there, and the CV mode before it.
  const auto at = [&](double s) {
    return static_cast<std::size_t>(std::lround(s / scenario.time_step_s));
  };
  EXPECT_GT(t.mean_probabilities[at(15.0)](2), 0.8);
  EXPECT_GT(t.mean_probabilities[at(8.0)](0), 0.5);
  double ca_turn = 0.0;
  double imm_turn = 0.0;
  double ca_anees = 0.0;
  double imm_anees = 0.0;
  for (std::size_t k = at(10.0); k < at(18.0); ++k) {
    ca_turn += t.rmse_ca_m[k];
    imm_turn += t.rmse_imm_m[k];
    ca_anees += t.anees_ca[k];
    imm_anees += t.anees_imm[k];
  }
  EXPECT_LT(imm_turn, 0.7 * ca_turn);
  EXPECT_LT(imm_anees, ca_anees);
}

}  // namespace
}  // namespace skyfuse
