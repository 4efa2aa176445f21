// The station network's IMM: peers fusing per-mode increments with the likelihood terms equal
// the central stacked IMM, and the IMM follows paper 000's turn where the CA filter lags.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "skyfuse/experiments/paper000_imm.hpp"
#include "skyfuse/fusion/fused_likelihood.hpp"
#include "skyfuse/fusion/stacked_likelihood.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/tracking/network_imm.hpp"
#include "skyfuse/validation/nis_gate.hpp"

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
      compare_central_and_peers(scenario, k300KmhInMps, 4, 0, scenario.steps);
  EXPECT_EQ(c.steps, 2000);
  EXPECT_TRUE(c.peers_identical);
  EXPECT_LT(c.max_position_difference_m, 1e-9);
  EXPECT_LT(c.max_probability_difference, 1e-9);
  EXPECT_NEAR(c.final_probabilities.sum(), 1.0, 1e-12);
}

TEST(NetworkImm, FollowsTheTurnWhereTheCaFilterLags) {
  const Scenario scenario = load_default_scenario();
  const TurnComparison t = imm_against_ca(scenario, k300KmhInMps, 4, 5);
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

// Two peers of paper 000's IMM and three radars measuring a target ahead of the prior.
struct TwoPeers {
  using Peers =
      PeerImm<KinematicState, ConstantVelocity3D, ConstantAcceleration3D, CoordinatedTurn3D>;
  using Radar = RangeAzimuthElevation<9>;
  Scenario scenario = load_default_scenario();
  GaussianState<9> start{
      (Vector<9>() << 0.0, 0.0, 400.0, 80.0, 10.0, 0.0, 0.0, 0.0, 0.0).finished(),
      Covariance<9>::Identity()};
  Peers a{NetworkImm<DefaultImmModes>::make(scenario, start)};
  Peers b{NetworkImm<DefaultImmModes>::make(scenario, start)};
  std::vector<StationObservation<Radar>> observations;

  TwoPeers() {
    const Vector3 sites[] = {{0.0, 0.0, 20.0}, {900.0, 300.0, 40.0}, {-500.0, 800.0, 10.0}};
    for (int i = 0; i < 3; ++i) {
      const Radar radar(sites[i]);
      observations.push_back({i + 1, radar, radar.predict(start.mean) + Vector3(0.3, 1e-3, 0.0),
                              Vector3(0.01, 1e-4, 1e-4).asDiagonal()});
    }
  }
  static bool same_bits(const Peers& x, const Peers& y) {
    const auto& f = x.filter();
    const auto& g = y.filter();
    return f.mode_probabilities() == g.mode_probabilities() &&
           f.mode_state<0>().mean == g.mode_state<0>().mean &&
           f.mode_state<0>().covariance == g.mode_state<0>().covariance &&
           f.mode_state<1>().mean == g.mode_state<1>().mean &&
           f.mode_state<1>().covariance == g.mode_state<1>().covariance &&
           f.mode_state<2>().mean == g.mode_state<2>().mean &&
           f.mode_state<2>().covariance == g.mode_state<2>().covariance;
  }
};

TEST(PeerImm, APeerThatLostAContributionTakesTheReferencePriorAndHoldsThePeersBitsAgain) {
  TwoPeers t;
  const std::vector<double> weights(3, 1.0);
  // Round 1: b loses station 1's contribution, so the two peers part.
  std::vector<TwoPeers::Peers::Contribution> c(3);
  for (std::size_t i = 0; i < 3; ++i) {
    ASSERT_EQ(t.a.contribute(t.observations[i], NisGate{}, c[i]).status, NumericalStatus::kOk);
  }
  const std::vector<const TwoPeers::Peers::Contribution*> all = {&c[0], &c[1], &c[2]};
  EXPECT_FALSE(t.a.fuse_round(all, weights).resynced);
  EXPECT_FALSE(t.b.fuse_round(std::vector{&c[1], &c[2]}, weights).resynced);
  t.a.predict();
  t.b.predict();
  ASSERT_FALSE(TwoPeers::same_bits(t.a, t.b));

  // Round 2: station 1 (peer a) and station 2 (peer b) contribute against their own priors;
  // both peers fuse all three onto station 1's, and hold the same bits again.
  ASSERT_EQ(t.a.contribute(t.observations[0], NisGate{}, c[0]).status, NumericalStatus::kOk);
  for (std::size_t i = 1; i < 3; ++i) {
    ASSERT_EQ(t.b.contribute(t.observations[i], NisGate{}, c[i]).status, NumericalStatus::kOk);
  }
  EXPECT_FALSE(t.a.fuse_round(all, weights).resynced);
  EXPECT_TRUE(t.b.fuse_round(all, weights).resynced);
  EXPECT_TRUE(TwoPeers::same_bits(t.a, t.b));
}

TEST(PeerImm, AScreenedOutMeasurementMovesNoModeStateAndNoProbability) {
  TwoPeers t;
  TwoPeers::Peers::Contribution c;
  StationObservation<TwoPeers::Radar> wild = t.observations[0];
  wild.z(0) += 500.0;  // 500 m off in range: far outside the 99 % gate
  const OwnContribution own = t.a.contribute(wild, NisGate::at_probability(0.99), c);
  ASSERT_EQ(own.refused, DropKind::kNisGate);
  EXPECT_EQ(c.terms[1].measurement_dim, 0);
  EXPECT_TRUE(std::get<2>(c.modes).increment.delta_information.isZero());
  const auto before = t.a.filter();
  ASSERT_EQ(t.a.fuse_round(std::vector{&c}, std::vector{1.0}).status, NumericalStatus::kOk);
  EXPECT_EQ(t.a.filter().mode_state<1>().mean, before.mode_state<1>().mean);
  EXPECT_EQ(t.a.filter().mode_state<2>().covariance, before.mode_state<2>().covariance);
  EXPECT_LT((t.a.filter().mode_probabilities() - before.mode_probabilities()).cwiseAbs().maxCoeff(),
            1e-15);

  // The center screens the same measurement out against its own (equal) prior.
  CentralImm<KinematicState, ConstantVelocity3D, ConstantAcceleration3D, CoordinatedTurn3D> central(
      NetworkImm<DefaultImmModes>::make(t.scenario, t.start));
  const std::array<const StationObservation<TwoPeers::Radar>*, 2> arrived = {&wild,
                                                                             &t.observations[1]};
  std::vector<int> refused;
  std::vector<int> stacked;
  ASSERT_EQ(central.update<StationObservation<TwoPeers::Radar>>(
                2, [&](std::size_t i) { return arrived[i]; }, NisGate::at_probability(0.99),
                [&](int id, DropKind) { refused.push_back(id); }, stacked),
            NumericalStatus::kOk);
  EXPECT_EQ(refused, std::vector{1});
  EXPECT_EQ(stacked, std::vector{2});
}

}  // namespace
}  // namespace skyfuse
