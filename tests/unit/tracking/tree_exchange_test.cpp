// The tree exchange's arithmetic: clusters of k by ascending id, each cluster's weighted sum of
// its members' increments, the clusters' sums into the round's total, and the total fused onto
// the lowest contributor's prior. It is the flat fusion in another order of summation (equal
// within rounding), fixed so that every node forming it forms the same bits, and what an
// aggregator computes from its members' slots alone gives the bits of the whole round's fuse().
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "skyfuse/models/constant_acceleration.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/tracking/cluster_layout.hpp"
#include "skyfuse/tracking/round_rule.hpp"

namespace skyfuse {
namespace {

using Model = ConstantAcceleration3D;
using Sensor = RangeAzimuthElevation<9>;
using State = GaussianState<9>;

const Model kMotion(0.02, {0.5, 0.1, 0.05});

State prior() {
  State s;
  s.mean << 0.0, 0.0, 400.0, 30.0, 5.0, 0.0, 0.0, 0.0, 0.0;
  s.covariance = Covariance<9>::Identity() * 25.0;
  return s;
}

bool same_bits(const State& a, const State& b) {
  return std::memcmp(a.mean.data(), b.mean.data(), sizeof(double) * 9) == 0 &&
         std::memcmp(a.covariance.data(), b.covariance.data(), sizeof(double) * 81) == 0;
}

// M radars on a ring around the target, each measuring it with a small offset of its own, their
// increments against `prior()` and weights that differ by station.
struct Round {
  std::vector<int> ids;
  std::vector<double> weights;
  std::vector<InformationIncrement<9>> increments;
  std::vector<State> priors;

  explicit Round(int m) {
    const State p = prior();
    for (int i = 0; i < m; ++i) {
      const double angle = 0.4 * i;
      const Sensor radar(Vector3(900.0 * std::cos(angle), 900.0 * std::sin(angle), 20.0 + i));
      const Vector3 z = radar.predict(p.mean) + Vector3(0.05 * (i % 3), 1e-3 * (i % 5 - 2), 2e-4);
      InformationIncrement<9> increment;
      EXPECT_EQ(compute_increment(3 * i + 1, p, radar, z,
                                  Covariance<3>(Vector3(0.01, 1e-4, 1e-4).asDiagonal()), increment),
                NumericalStatus::kOk);
      ids.push_back(3 * i + 1);  // ascending, not consecutive
      weights.push_back(1.0 + 0.1 * (i % 4));
      increments.push_back(increment);
      priors.push_back(p);
    }
  }
  // slot_at for a round where `arrived(i)` says who arrived.
  template <typename Arrived>
  auto slots(Arrived arrived) const {
    return [this, arrived](std::size_t i) {
      return arrived(i) ? PeerSlot<9>{&increments[i], &priors[i]} : PeerSlot<9>{};
    };
  }
};

TEST(ClusterLayout, CutsTheAscendingIdsIntoConsecutiveClustersOfTheFanout) {
  const std::vector<int> ids = {2, 3, 5, 8, 13, 21, 34, 55, 89, 144};
  const ClusterLayout layout(ids, 4);
  EXPECT_EQ(layout.clusters(), 3u);
  EXPECT_EQ(std::vector<int>(layout.members(0).begin(), layout.members(0).end()),
            (std::vector<int>{2, 3, 5, 8}));
  EXPECT_EQ(std::vector<int>(layout.members(2).begin(), layout.members(2).end()),
            (std::vector<int>{89, 144}));
  EXPECT_EQ(layout.cluster_of_id(13), 1u);
  EXPECT_EQ(layout.cluster_of_id(144), 2u);
  EXPECT_EQ(layout.cluster_of_id(4), layout.clusters()) << "not a participant";
  EXPECT_EQ(ClusterLayout(ids, 16).clusters(), 1u);
  EXPECT_THROW(ClusterLayout(ids, 0), std::invalid_argument);
}

TEST(TreeExchange, FusesTheFlatRoundsEstimateWithinRounding) {
  const Round round(16);
  const auto all = round.slots([](std::size_t) { return true; });
  PeerTracker<Model> flat(kMotion, prior());
  PeerTracker<Model> tree(kMotion, prior());
  PeerRound<Model> flat_round(round.ids, round.weights);
  PeerRound<Model> tree_round(round.ids, round.weights, 4);
  ASSERT_EQ(flat_round.fuse(flat, all).status, NumericalStatus::kOk);
  ASSERT_EQ(tree_round.fuse(tree, all).status, NumericalStatus::kOk);

  EXPECT_LT((flat.estimate().mean - tree.estimate().mean).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((flat.estimate().covariance - tree.estimate().covariance).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(std::vector<int>(tree_round.contributors().begin(), tree_round.contributors().end()),
            round.ids);
  // It moved the estimate: the measurements say something.
  EXPECT_GT((tree.estimate().mean - prior().mean).norm(), 0.01);
}

TEST(TreeExchange, AnAggregatorsSumsGiveEveryPeerTheBitsOfTheWholeRound) {
  const Round round(16);
  // Stations 2 and 9 (positions) lost; cluster 3 (positions 12-15) lost whole.
  const auto arrived = round.slots([](std::size_t i) { return i != 2 && i != 9 && i < 12; });
  PeerRound<Model> whole(round.ids, round.weights, 4);
  PeerTracker<Model> reference(kMotion, prior());
  ASSERT_EQ(whole.fuse(reference, arrived).status, NumericalStatus::kOk);

  // What the aggregators do: each sums its own cluster; the sums are added in cluster order
  // into the total a peer fuses.
  PeerRound<Model> aggregators(round.ids, round.weights, 4);
  PartialSum<9> total;
  total.clear();
  for (std::size_t c = 0; c < aggregators.layout()->clusters(); ++c) {
    PartialSum<9> cluster;
    aggregators.sum_cluster(c, arrived, cluster);
    total.add(cluster);
  }
  PeerRound<Model> member(round.ids, round.weights, 4);
  PeerTracker<Model> peer(kMotion, prior());
  ASSERT_EQ(member.fuse_total(peer, total).status, NumericalStatus::kOk);
  EXPECT_TRUE(same_bits(peer.estimate(), reference.estimate()));
  EXPECT_EQ(std::vector<int>(member.contributors().begin(), member.contributors().end()),
            std::vector<int>(whole.contributors().begin(), whole.contributors().end()));
  EXPECT_EQ(total.contributors.size(), 10u);
}

TEST(TreeExchange, FusesOntoTheLowestContributorsPriorAndNothingWhenNothingArrived) {
  Round round(8);
  State other = prior();
  other.mean(0) += 0.5;
  for (std::size_t i = 0; i < 8; ++i) round.priors[i] = other;
  round.priors[5] = prior();  // the lowest to arrive below
  PeerRound<Model> tree(round.ids, round.weights, 4);
  PeerTracker<Model> from_own(kMotion, other);
  const RoundFusion fused = tree.fuse(from_own, round.slots([](std::size_t i) { return i >= 5; }));
  ASSERT_EQ(fused.status, NumericalStatus::kOk);
  EXPECT_TRUE(fused.resynced) << "the reference was station 16's prior, not this peer's";

  PeerTracker<Model> untouched(kMotion, prior());
  const RoundFusion none = tree.fuse(untouched, round.slots([](std::size_t) { return false; }));
  EXPECT_EQ(none.status, NumericalStatus::kOk);
  EXPECT_FALSE(tree.arrived());
  EXPECT_TRUE(same_bits(untouched.estimate(), prior()));
}

}  // namespace
}  // namespace skyfuse
