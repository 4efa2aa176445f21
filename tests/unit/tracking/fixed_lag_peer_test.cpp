// Fixed-lag re-fusion: a late contribution within the lag is fused again where it belongs, so a
// peer that got it late holds the same bits as one that got it in time; without a lag it is
// lost; and with nothing late, a lag changes no bit of the round rule. The senders carry the
// peer's own prior, as in-step stations do.
#include "skyfuse/tracking/fixed_lag_peer.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "skyfuse/models/constant_acceleration.hpp"

namespace skyfuse {
namespace {

using Model = ConstantAcceleration3D;
using Contribution = PeerContribution<9>;

const Model kMotion(0.02, {0.5, 0.1, 0.05});
const std::vector<int> kIds = {1, 2, 3};
const std::vector<double> kWeights = {1.0, 1.0, 1.0};

GaussianState<9> initial() {
  GaussianState<9> s;
  s.mean << 100.0, 200.0, 50.0, 10.0, 0.0, 0.0, 0.0, 0.0, 0.0;
  s.covariance = Covariance<9>::Identity() * 25.0;
  return s;
}

// Station `id`'s contribution to round k: position information along one axis, about the
// prior it carries (`prior`: the senders here are in step with the peer under test, as in a
// network without loss).
Contribution contribution(int id, std::uint64_t k, const GaussianState<9>& prior) {
  Contribution c;
  c.increment.station_id = id;
  const int axis = (id - 1) % 3;
  c.increment.delta_information(axis, axis) = 4.0;
  c.increment.delta_vector(axis) = 4.0 * (100.0 + static_cast<double>(id * 7 + k));
  c.prior = prior;
  return c;
}

auto round_rule(FixedLagPeer<Model>& peer) {
  return
      [&peer](std::uint64_t, auto slot_at) { return peer.round().fuse(peer.tracker(), slot_at); };
}

enum class Late { kNone, kDelivered, kLost };

// Runs rounds 0..steps-1; station 3's contribution to round `late_round` arrives only after
// that round closed (kDelivered), or never (kLost). Returns the estimate after the last round.
GaussianState<9> run(std::size_t lag, Late late, int late_round = 3, int steps = 6) {
  FixedLagPeer<Model> peer(kMotion, initial(), kIds, kWeights, lag);
  GaussianState<9> late_prior;
  for (int k = 0; k < steps; ++k) {
    const auto step = static_cast<std::uint64_t>(k);
    if (late == Late::kDelivered && k == late_round + 1) {
      const auto r = static_cast<std::uint64_t>(late_round);
      const auto why = peer.collector().offer(r, 3, contribution(3, r, late_prior));
      if (lag == 0) {
        EXPECT_EQ(why, DropKind::kStaleStep);
      } else {
        EXPECT_EQ(why, std::nullopt);
        peer.kept(r);
      }
    }
    EXPECT_EQ(peer.refresh_prior(round_rule(peer)), NumericalStatus::kOk);
    const GaussianState<9> prior = peer.tracker().estimate();
    for (int id : kIds) {
      if (id == 3 && k == late_round && late != Late::kNone) {
        late_prior = prior;
        continue;
      }
      EXPECT_EQ(peer.collector().offer(step, id, contribution(id, step, prior)), std::nullopt);
    }
    EXPECT_EQ(peer.fuse_current(round_rule(peer)).status, NumericalStatus::kOk);
    if (k + 1 < steps) {
      peer.predict();
      peer.advance();
    }
  }
  return peer.tracker().estimate();
}

TEST(FixedLagPeer, WithNothingLateALagChangesNoBitOfTheRoundRule) {
  const GaussianState<9> plain = run(0, Late::kNone);
  for (std::size_t lag : {1U, 3U}) {
    const GaussianState<9> lagged = run(lag, Late::kNone);
    EXPECT_EQ(lagged.mean, plain.mean) << lag;
    EXPECT_EQ(lagged.covariance, plain.covariance) << lag;
  }
}

TEST(FixedLagPeer, ALateContributionWithinTheLagGivesTheBitsOfOneInTime) {
  // Round 3's sample arrives during round 4; with a lag it is fused into round 3 again.
  for (std::size_t lag : {1U, 3U}) {
    const GaussianState<9> in_time = run(lag, Late::kNone);
    const GaussianState<9> late = run(lag, Late::kDelivered);
    EXPECT_EQ(late.mean, in_time.mean) << lag;
    EXPECT_EQ(late.covariance, in_time.covariance) << lag;
    // Never delivered, it is missing, and the estimate differs: the equality is no accident.
    EXPECT_NE(run(lag, Late::kLost).mean, in_time.mean) << lag;
  }
  // Without a lag the late sample is refused (stale) and lost as well.
  EXPECT_NE(run(0, Late::kDelivered).mean, run(0, Late::kNone).mean);
}

TEST(FixedLagPeer, SettlesEachRoundAsItLeavesTheLagAndTheRestAtTheEnd) {
  FixedLagPeer<Model> peer(kMotion, initial(), kIds, kWeights, 2);
  std::vector<std::uint64_t> settled;
  for (std::uint64_t k = 0; k < 5; ++k) {
    const GaussianState<9> prior = peer.tracker().estimate();
    for (int id : kIds) {
      ASSERT_EQ(peer.collector().offer(k, id, contribution(id, k, prior)), std::nullopt);
    }
    ASSERT_EQ(peer.fuse_current(round_rule(peer)).status, NumericalStatus::kOk);
    if (const auto s = peer.settled_round()) settled.push_back(*s);
    peer.predict();
    peer.advance();
  }
  EXPECT_EQ(settled, (std::vector<std::uint64_t>{0, 1, 2}));
  NumericalStatus status = NumericalStatus::kNotPositiveDefinite;
  const auto [from, to] = peer.settle_rest(round_rule(peer), status);
  EXPECT_EQ(status, NumericalStatus::kOk);
  EXPECT_EQ(from, 3U);
  EXPECT_EQ(to, 5U);
  EXPECT_EQ(std::vector<int>(peer.contributors_of(4).begin(), peer.contributors_of(4).end()), kIds);
  EXPECT_EQ(peer.late_used(), 0U);
}

}  // namespace
}  // namespace skyfuse
