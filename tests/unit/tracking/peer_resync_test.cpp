// Peers that lose different increments drift apart; the reference-prior rule of fuse_round()
// must bring them back to the same bits in the first round in which every peer receives every
// increment. In-process, with the same loss model the DDS runs use.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "skyfuse/models/constant_acceleration.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/random/link_delay.hpp"
#include "skyfuse/random/link_loss.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/sim/run_plan.hpp"
#include "skyfuse/tracking/round_rule.hpp"

namespace skyfuse {
namespace {

struct PeerRun {
  std::vector<double> spread;  ///< per step: max |difference| over every peer's mean and P
  double rmse_m = 0.0;         ///< over every peer and step
  int resyncs = 0;
};

double difference(const GaussianState<9>& a, const GaussianState<9>& b) {
  return std::max((a.mean - b.mean).cwiseAbs().maxCoeff(),
                  (a.covariance - b.covariance).cwiseAbs().maxCoeff());
}

PeerRun run_peers(const LinkLoss& loss, int stations = 4, int steps = 300) {
  RunOverrides overrides;
  overrides.stations = stations;
  overrides.steps = steps;
  const RunPlan plan = make_run_plan(load_default_scenario(), overrides);
  const TruthTrajectory truth = plan.truth();
  const auto motion = plan.motion_model<ConstantAcceleration3D>();
  const GaussianState<9> initial =
      initial_estimate<ConstantAcceleration3D>(plan.scenario, truth.states.front(), plan.mc_run);
  const auto m = static_cast<std::size_t>(stations);
  std::vector<PeerTracker<ConstantAcceleration3D>> peers(m, PeerTracker(motion, initial));

  // Ascending id, as every receiver orders its round.
  std::vector<StationConfig> by_id(plan.participants().begin(), plan.participants().end());
  std::sort(by_id.begin(), by_id.end(), [](auto& a, auto& b) { return a.id < b.id; });

  std::vector<int> ids;
  std::vector<double> weights;
  for (const StationConfig& s : by_id) {
    ids.push_back(s.id);
    weights.push_back(s.weight);
  }
  PeerRound<ConstantAcceleration3D> round(ids, weights);

  PeerRun out;
  double sq = 0.0;
  std::vector<PeerContribution<9>> sent(m);
  for (int k = 0; k < steps; ++k) {
    const auto step = static_cast<std::uint64_t>(k);
    for (std::size_t i = 0; i < m; ++i) {
      StationObservation<RangeAzimuthElevation<9>> measured;
      measured.station_id = by_id[i].id;
      measured.sensor = RangeAzimuthElevation<9>(by_id[i].position_m);
      measured.noise = station_noise_covariance<3>(plan.scenario, by_id[i], plan.mc_run);
      measured.z = simulate_measurement(measured.sensor, truth.states[step], measured.noise,
                                        plan.scenario.seed, plan.mc_run, by_id[i].id, step);
      sent[i].prior = peers[i].estimate();
      const OwnContribution own = contribute(sent[i].prior, measured, NisGate{}, sent[i].increment);
      EXPECT_EQ(own.status, NumericalStatus::kOk);
      EXPECT_FALSE(own.refused);
    }
    // Each peer fuses what reached it, by the round rule every station follows.
    for (std::size_t r = 0; r < m; ++r) {
      const RoundFusion fused = round.fuse(peers[r], [&](std::size_t s) {
        if (loss.lost(by_id[r].id, by_id[s].id, step)) return PeerSlot<9>{};
        return PeerSlot<9>{&sent[s].increment, &sent[s].prior};
      });
      EXPECT_EQ(fused.status, NumericalStatus::kOk);
      if (fused.resynced) ++out.resyncs;
    }
    double spread = 0.0;
    for (std::size_t r = 0; r < m; ++r) {
      spread = std::max(spread, difference(peers[r].estimate(), peers[0].estimate()));
      sq += (peers[r].estimate().mean.head<3>() - truth.states[step].head<3>()).squaredNorm();
    }
    out.spread.push_back(spread);
    for (auto& peer : peers) peer.predict();
  }
  out.rmse_m = std::sqrt(sq / static_cast<double>(steps * stations));
  return out;
}

TEST(PeerResync, WithoutLossEveryPeerHoldsTheSameBitsAndNeverResyncs) {
  const PeerRun run = run_peers(LinkLoss{});
  EXPECT_EQ(*std::max_element(run.spread.begin(), run.spread.end()), 0.0);
  EXPECT_EQ(run.resyncs, 0);
}

TEST(PeerResync, PeersThatLostDifferentIncrementsAgreeAgainInTheFirstCompleteRound) {
  LinkLoss loss;
  loss.probability = 0.2;
  loss.first_step = 100;
  loss.end_step = 200;
  const PeerRun run = run_peers(loss);
  // Before the loss: identical. During: apart. From the first lossless round on: identical.
  EXPECT_EQ(*std::max_element(run.spread.begin(), run.spread.begin() + 100), 0.0);
  EXPECT_GT(*std::max_element(run.spread.begin() + 100, run.spread.begin() + 200), 0.0);
  EXPECT_EQ(*std::max_element(run.spread.begin() + 200, run.spread.end()), 0.0);
  EXPECT_GT(run.resyncs, 0);
}

TEST(PeerResync, TwentyPercentLossAtMostDoublesTheError) {
  const PeerRun lossless = run_peers(LinkLoss{});
  LinkLoss loss;
  loss.probability = 0.2;
  const PeerRun lossy = run_peers(loss);
  EXPECT_GT(lossy.resyncs, 0);
  EXPECT_LE(lossy.rmse_m, 2.0 * lossless.rmse_m)
      << "lossless " << lossless.rmse_m << " m, 20 % loss " << lossy.rmse_m << " m";
}

// A round that cannot be fused (here the reference prior is not positive definite) leaves
// the peer's estimate as it was: the station reports the failure with the state it held.
TEST(PeerResync, AFailedRoundLeavesTheEstimateAndIsNoResync) {
  GaussianState<9> initial;
  initial.mean.setConstant(1.0);
  initial.covariance.setIdentity();
  PeerTracker peer(ConstantAcceleration3D(0.02, {0.5, 0.1, 0.05}), initial);
  GaussianState<9> reference = initial;
  reference.mean(0) = 2.0;
  reference.covariance(4, 4) = -1.0;
  const std::vector<InformationIncrement<9>> none;
  const std::vector<double> no_weights;
  const RoundFusion fused = peer.fuse_round(reference, none, no_weights);
  EXPECT_EQ(fused.status, NumericalStatus::kNotPositiveDefinite);
  EXPECT_FALSE(fused.resynced);
  EXPECT_EQ(peer.estimate().mean, initial.mean);
  EXPECT_EQ(peer.estimate().covariance, initial.covariance);

  // The same reference made valid: adopted, and reported as a resync.
  reference.covariance(4, 4) = 1.0;
  const RoundFusion adopted = peer.fuse_round(reference, none, no_weights);
  EXPECT_EQ(adopted.status, NumericalStatus::kOk);
  EXPECT_TRUE(adopted.resynced);
  EXPECT_NEAR(peer.estimate().mean(0), 2.0, 1e-12);
}

TEST(LinkLoss, DrawsArePureFunctionsOfLinkAndStepAndMatchTheRate) {
  LinkLoss loss;
  loss.probability = 0.2;
  loss.seed = 7;
  int lost = 0;
  const int n = 20000;
  for (int k = 0; k < n; ++k) {
    const bool once = loss.lost(1, 2, static_cast<std::uint64_t>(k));
    EXPECT_EQ(once, loss.lost(1, 2, static_cast<std::uint64_t>(k)));
    lost += once ? 1 : 0;
  }
  // Binomial(20000, 0.2): sd = 57; 5 sd either side.
  EXPECT_NEAR(lost, 0.2 * n, 5 * 57);
  EXPECT_FALSE(loss.lost(3, 3, 0)) << "a node never loses its own sample";
  loss.first_step = 10;
  loss.end_step = 20;
  for (int k = 0; k < 10; ++k) EXPECT_FALSE(loss.lost(1, 2, static_cast<std::uint64_t>(k)));
  for (int k = 20; k < 100; ++k) EXPECT_FALSE(loss.lost(1, 2, static_cast<std::uint64_t>(k)));
}

TEST(LinkDelay, DrawsArePureFunctionsOfLinkAndStepWithinTheJitterAndReorderLinks) {
  using std::chrono::microseconds;
  const LinkDelay delay{10.0, 8.0};
  double sum_ms = 0.0;
  int reordered = 0;
  const int n = 20000;
  for (int k = 0; k < n; ++k) {
    const auto step = static_cast<std::uint64_t>(k);
    const microseconds d = delay.of(7, 1, 2, step);
    EXPECT_EQ(d, delay.of(7, 1, 2, step));
    EXPECT_GE(d, microseconds(2000));
    EXPECT_LE(d, microseconds(18000));
    sum_ms += static_cast<double>(d.count()) / 1000.0;
    reordered += delay.of(7, 1, 3, step) < d ? 1 : 0;  // station 3's sample overtakes 2's
  }
  // Uniform on [2, 18] ms: sd 4.6 ms, of the mean of 20000 draws 0.033 ms; 5 sd either side.
  EXPECT_NEAR(sum_ms / n, 10.0, 5 * 0.033);
  EXPECT_NEAR(reordered, n / 2, 5 * 71);  // Binomial(20000, 1/2): sd 71
  EXPECT_NE(delay.of(8, 1, 2, 0), delay.of(7, 1, 2, 0)) << "the seed matters";
  EXPECT_EQ(delay.of(7, 3, 3, 0), microseconds(0)) << "a node's own sample is not delayed";
  // Never below zero, however large the jitter.
  const LinkDelay wide{1.0, 5.0};
  for (int k = 0; k < 1000; ++k) {
    EXPECT_GE(wide.of(7, 1, 2, static_cast<std::uint64_t>(k)), microseconds(0));
  }
  EXPECT_FALSE(LinkDelay{}.enabled());
  EXPECT_EQ(LinkDelay{}.of(7, 1, 2, 0), microseconds(0));
}

}  // namespace
}  // namespace skyfuse
