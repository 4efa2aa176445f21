#include "skyfuse/tracking/round_rule.hpp"

#include <gtest/gtest.h>

#include <random>

#include "skyfuse/models/constant_acceleration.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "support/random_problems.hpp"

namespace skyfuse {
namespace {

using Model = ConstantAcceleration3D;
using Sensor = RangeAzimuthElevation<9>;
using Observation = StationObservation<Sensor>;

const Model kModel(0.02, {0.5, 0.1, 0.05});

// Three stations around a target near (0, 0, 400), each measuring it exactly; station 2's range
// is `range_offset_m` off.
struct Round {
  GaussianState<9> prior;
  std::vector<Observation> observations;  // ascending id: 1, 2, 3
};

Round make_round(double range_offset_m) {
  std::mt19937 rng(5);
  Round r;
  r.prior = test::random_prior(rng, Vector3(0.0, 0.0, 400.0));
  const Vector3 sites[] = {{-800.0, 100.0, 20.0}, {600.0, -700.0, 30.0}, {300.0, 900.0, 10.0}};
  for (int i = 0; i < 3; ++i) {
    Observation o;
    o.station_id = i + 1;
    o.sensor = Sensor(sites[i]);
    o.noise = Vector3(0.1 * 0.1, 1e-4, 1e-4).asDiagonal();
    o.z = o.sensor.predict(r.prior.mean);
    r.observations.push_back(o);
  }
  r.observations[1].z(Sensor::kRange) += range_offset_m;
  return r;
}

TEST(RoundRule, AScreenedOutMeasurementContributesAZeroIncrementAndSaysWhy) {
  const Round r = make_round(200.0);
  const NisGate gate = NisGate::at_probability(0.9999);
  InformationIncrement<9> increment;
  increment.delta_vector.setOnes();
  const OwnContribution outlier = contribute(r.prior, r.observations[1], gate, increment);
  EXPECT_EQ(outlier.refused, DropKind::kNisGate);
  EXPECT_EQ(increment.station_id, 2);
  EXPECT_TRUE(increment.delta_information.isZero(0.0));
  EXPECT_TRUE(increment.delta_vector.isZero(0.0));

  Observation garbage = r.observations[0];
  garbage.z(Sensor::kRange) = -1.0;
  EXPECT_EQ(contribute(r.prior, garbage, gate, increment).refused, DropKind::kOutOfRange);

  const OwnContribution good = contribute(r.prior, r.observations[0], gate, increment);
  EXPECT_FALSE(good.refused);
  InformationIncrement<9> direct;
  compute_increment(1, r.prior, r.observations[0].sensor, r.observations[0].z,
                    r.observations[0].noise, direct);
  EXPECT_EQ(increment.delta_information, direct.delta_information);
  EXPECT_EQ(increment.delta_vector, direct.delta_vector);
}

TEST(RoundRule, PeersFuseWhatArrivedInIdOrderOntoTheLowestIdsPrior) {
  const Round r = make_round(0.0);
  std::vector<PeerContribution<9>> sent(3);
  for (std::size_t i = 0; i < 3; ++i) {
    sent[i].prior = r.prior;
    contribute(r.prior, r.observations[i], NisGate{}, sent[i].increment);
  }
  // Station 1's contribution is lost; station 2's prior is the reference, not this peer's own.
  sent[1].prior.mean(0) += 1.0;
  const int ids[] = {1, 2, 3};
  const double weights[] = {1.0, 1.0, 1.0};
  PeerRound<Model> round(ids, weights);
  PeerTracker<Model> peer(kModel, r.prior);
  const RoundFusion fused = round.fuse(peer, [&](std::size_t i) {
    if (i == 0) return PeerSlot<9>{};
    return PeerSlot<9>{&sent[i].increment, &sent[i].prior};
  });
  EXPECT_EQ(fused.status, NumericalStatus::kOk);
  EXPECT_TRUE(fused.resynced);
  ASSERT_EQ(round.contributors().size(), 2U);
  EXPECT_EQ(round.contributors()[0], 2);
  EXPECT_EQ(round.contributors()[1], 3);

  GaussianState<9> expected;
  const InformationIncrement<9> both[] = {sent[1].increment, sent[2].increment};
  ASSERT_EQ(fuse_increments<9>(sent[1].prior, std::span<const InformationIncrement<9>>(both),
                               std::span<const double>(weights, 2), expected),
            NumericalStatus::kOk);
  EXPECT_EQ(peer.estimate().mean, expected.mean);
  EXPECT_EQ(peer.estimate().covariance, expected.covariance);

  const GaussianState<9> before = peer.estimate();
  const RoundFusion nothing = round.fuse(peer, [](std::size_t) { return PeerSlot<9>{}; });
  EXPECT_EQ(nothing.status, NumericalStatus::kOk);
  EXPECT_FALSE(round.arrived());
  EXPECT_EQ(peer.estimate().mean, before.mean);
}

TEST(RoundRule, TheCenterStacksWhatPassesInIdOrderAndAgreesWithThePeers) {
  const Round r = make_round(200.0);  // station 2 is an outlier
  const NisGate gate = NisGate::at_probability(0.9999);
  CentralTracker<Model, Sensor> center(kModel, r.prior);
  CentralRound<Model, Sensor> central_round(3);
  std::vector<std::pair<int, DropKind>> refused;
  const UpdateReport report = central_round.update(
      center, 3, [&](std::size_t i) { return &r.observations[i]; }, gate,
      [&](int id, DropKind why) { refused.emplace_back(id, why); });
  EXPECT_EQ(report.status, NumericalStatus::kOk);
  ASSERT_EQ(refused.size(), 1U);
  EXPECT_EQ(refused[0], std::make_pair(2, DropKind::kNisGate));
  ASSERT_EQ(central_round.contributors().size(), 2U);
  EXPECT_EQ(central_round.contributors()[0], 1);
  EXPECT_EQ(central_round.contributors()[1], 3);

  // The same stacked update by hand, on stations 1 and 3.
  GaussianState<9> by_hand = r.prior;
  StackedEkf<9, Sensor> stacked;
  const Observation passing[] = {r.observations[0], r.observations[2]};
  stacked.update(by_hand, std::span<const Observation>(passing));
  EXPECT_EQ(center.estimate().mean, by_hand.mean);

  // The peers, screening their own measurements against the same prior, fuse the same two.
  std::vector<PeerContribution<9>> sent(3);
  for (std::size_t i = 0; i < 3; ++i) {
    sent[i].prior = r.prior;
    contribute(r.prior, r.observations[i], gate, sent[i].increment);
  }
  const int ids[] = {1, 2, 3};
  const double weights[] = {1.0, 1.0, 1.0};
  PeerRound<Model> peer_round(ids, weights);
  PeerTracker<Model> peer(kModel, r.prior);
  peer_round.fuse(peer, [&](std::size_t i) {
    return PeerSlot<9>{&sent[i].increment, &sent[i].prior};
  });
  EXPECT_LT((peer.estimate().mean - center.estimate().mean).norm(), 1e-9);

  // Nothing passes: the center keeps its estimate.
  CentralTracker<Model, Sensor> empty(kModel, r.prior);
  const UpdateReport none = central_round.update(
      empty, 3, [](std::size_t) { return static_cast<const Observation*>(nullptr); }, gate,
      [](int, DropKind) {});
  EXPECT_EQ(none.status, NumericalStatus::kOk);
  EXPECT_EQ(empty.estimate().mean, r.prior.mean);
}

}  // namespace
}  // namespace skyfuse
