// The NCRKF in information form against its Eq 11, its refusal of an update whose fused
// information is not positive definite, what a received TDOA increment must be, and the round
// rule that fuses a round without its indefinite increments when it must, in the flat and the
// tree exchange's orders.
#include "skyfuse/filters/ncrkf.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>

#include "skyfuse/models/tdoa/tdoa_relative_motion.hpp"
#include "skyfuse/tracking/tdoa_partial_sum.hpp"
#include "skyfuse/tracking/tdoa_round.hpp"

namespace skyfuse {
namespace {

GaussianState<9> prior() {
  GaussianState<9> p;
  p.mean << 1800.0, 2400.0, 3000.0, -40.0, 12.0, -20.0, 0.0, 0.0, 0.0;
  p.covariance = Covariance<9>::Identity();
  p.covariance.diagonal().head<3>().setConstant(400.0);
  p.covariance.diagonal().segment<3>(3).setConstant(25.0);
  p.covariance(0, 3) = p.covariance(3, 0) = 20.0;
  return p;
}

std::vector<PseudoLinearTdoaRow> rows() {
  return {pseudo_linear_tdoa_row(Vector<2>(200.0, 0.0), -112.3, -112.3, 0.4),
          pseudo_linear_tdoa_row(Vector<2>(-200.0, 0.0), 126.1, 126.1, 0.4),
          pseudo_linear_tdoa_row(Vector<2>(0.0, 200.0), -152.8, -152.8, 0.4)};
}

TEST(Ncrkf, TheInformationFormIsEquation11) {
  const GaussianState<9> before = prior();
  GaussianState<9> fused = before;
  TdoaUpdateScratch scratch;
  ASSERT_EQ(tdoa_update(fused, rows(), BiasCompensation::kCompensated, scratch),
            NumericalStatus::kOk);

  // Eq 11: P+^-1 = P-^-1 + sum H^T R^-1 H - W;
  //        x+ = (I + P+ W) x- + P+ H^T R^-1 (y - H x-) - P+ V.
  Covariance<9> information = before.covariance.inverse();
  Covariance<9> w = Covariance<9>::Zero();
  Vector<9> v = Vector<9>::Zero();
  Vector<9> innovation_term = Vector<9>::Zero();
  for (const PseudoLinearTdoaRow& row : rows()) {
    information += row.h.transpose() * row.h / row.noise;
    w(2, 2) += row.w;
    v(2) += row.v;
    innovation_term += row.h.transpose() * ((row.y - row.h.dot(before.mean)) / row.noise);
  }
  information -= w;
  const Covariance<9> p = information.inverse();
  const Vector<9> x =
      (Covariance<9>::Identity() + p * w) * before.mean + p * innovation_term - p * v;
  EXPECT_LT((fused.mean - x).cwiseAbs().maxCoeff(), 1e-6 * x.cwiseAbs().maxCoeff());
  EXPECT_LT((fused.covariance - p).cwiseAbs().maxCoeff(), 1e-9 * p.cwiseAbs().maxCoeff());

  // Without compensation it is the plain KF (the nominal filter): W and V make a difference.
  GaussianState<9> nominal = before;
  ASSERT_EQ(tdoa_update(nominal, rows(), BiasCompensation::kNone, scratch), NumericalStatus::kOk);
  EXPECT_GT(std::abs(nominal.mean(2) - fused.mean(2)), 1e-6);
}

TEST(Ncrkf, ASingleIncrementMayBeIndefiniteAndAnUpdateThatIsNotPositiveDefiniteIsRefused) {
  // |r~| < sigma: the increment's d_t1 entry 4 r~^2 / R - W is negative.
  const PseudoLinearTdoaRow row = pseudo_linear_tdoa_row(Vector<2>(200.0, 0.0), 0.1, 0.1, 0.4);
  const auto increment = tdoa_increment(2, row, BiasCompensation::kCompensated);
  EXPECT_LT(increment.delta_information(2, 2), 0.0);

  // A prior that knows next to nothing of d_t1 cannot absorb it: the update is refused and the
  // state kept.
  GaussianState<9> state = prior();
  state.covariance(2, 2) = 1e12;
  const GaussianState<9> before = state;
  TdoaUpdateScratch scratch;
  const std::vector<PseudoLinearTdoaRow> one = {row};
  EXPECT_EQ(tdoa_update(state, one, BiasCompensation::kCompensated, scratch),
            NumericalStatus::kNotPositiveDefinite);
  EXPECT_EQ(state.mean, before.mean);
  EXPECT_EQ(state.covariance, before.covariance);
  // A prior that knows d_t1 to 0.1 m (information 100 against the increment's -10.4) takes it.
  GaussianState<9> confident = prior();
  confident.covariance(2, 2) = 0.01;
  EXPECT_EQ(tdoa_update(confident, one, BiasCompensation::kCompensated, scratch),
            NumericalStatus::kOk);
}

TEST(TdoaIncrementCheck, TakesEveryRealIncrementIndefiniteOnesIncludedAndRefusesGarbage) {
  constexpr double kSigma = 0.4;
  // Real increments over range differences from -150 m to 150 m, |r~| < sigma among them.
  for (double r = -150.0; r <= 150.0; r += 0.05) {
    const auto increment =
        tdoa_increment(2, pseudo_linear_tdoa_row(Vector<2>(200.0, 0.0), r, r, kSigma),
                       BiasCompensation::kCompensated);
    ASSERT_EQ(check_tdoa_increment(increment, kSigma), std::nullopt) << "r~ " << r;
  }
  const auto real =
      tdoa_increment(2, pseudo_linear_tdoa_row(Vector<2>(0.0, 200.0), 0.1, 0.1, kSigma),
                     BiasCompensation::kCompensated);
  ASSERT_TRUE(is_indefinite(real));
  // More indefinite than any W of this sigma.
  auto too_negative = real;
  too_negative.delta_information(2, 2) -= 2.0 / (kSigma * kSigma);
  EXPECT_EQ(check_tdoa_increment(too_negative, kSigma), DropKind::kNotPositive);
  // Information about a velocity or an acceleration: no TDOA receiver gives that.
  auto velocity = real;
  velocity.delta_information(4, 4) = 1.0;
  EXPECT_EQ(check_tdoa_increment(velocity, kSigma), DropKind::kOutOfRange);
  auto vector = real;
  vector.delta_vector(8) = 1.0;
  EXPECT_EQ(check_tdoa_increment(vector, kSigma), DropKind::kOutOfRange);
  auto nan = real;
  nan.delta_vector(0) = std::nan("");
  EXPECT_EQ(check_tdoa_increment(nan, kSigma), DropKind::kNonFinite);
  auto huge = real;
  huge.delta_information(0, 0) = 1e300;
  EXPECT_EQ(check_tdoa_increment(huge, kSigma), DropKind::kOutOfRange);
}

TEST(TdoaRound, ARoundThatIsNotPositiveDefiniteIsFusedAgainWithoutItsIndefiniteIncrements) {
  const TdoaRelativeMotion model(0.002, {0.1});
  GaussianState<9> start = prior();
  start.covariance(2, 2) = 1e12;  // knows next to nothing of d_t1: cannot absorb -W
  // Participant 2's increment is indefinite (|r~| < sigma); participant 3's is positive
  // semi-definite information about dx alone.
  const auto indefinite =
      tdoa_increment(2, pseudo_linear_tdoa_row(Vector<2>(200.0, 0.0), 0.1, 0.1, 0.4),
                     BiasCompensation::kCompensated);
  ASSERT_TRUE(is_indefinite(indefinite));
  InformationIncrement<9> along_x;
  along_x.station_id = 3;
  along_x.delta_information(0, 0) = 4.0;
  along_x.delta_vector(0) = 4.0 * 1801.0;
  const std::vector<InformationIncrement<9>> increments = {indefinite, along_x};
  const std::vector<int> ids = {2, 3};
  const std::vector<double> weights = {1.0, 1.0};

  PeerTracker<TdoaRelativeMotion> tracker(model, start);
  PeerRound<TdoaRelativeMotion> round(ids, weights);
  std::vector<std::size_t> refused;
  const RoundFusion fused = fuse_tdoa_round(
      round, tracker, ids.size(),
      [&](std::size_t i) {
        return PeerSlot<9>{&increments[i], &start};
      },
      [&](std::size_t i) { refused.push_back(i); });
  ASSERT_EQ(fused.status, NumericalStatus::kOk);
  EXPECT_EQ(refused, std::vector<std::size_t>{0});
  EXPECT_EQ(std::vector<int>(round.contributors().begin(), round.contributors().end()),
            std::vector<int>{3});

  // The same bits as a round of participant 3 alone.
  PeerTracker<TdoaRelativeMotion> alone(model, start);
  PeerRound<TdoaRelativeMotion> alone_round(ids, weights);
  ASSERT_EQ(alone_round
                .fuse(alone,
                      [&](std::size_t i) {
                        return i == 1 ? PeerSlot<9>{&increments[1], &start} : PeerSlot<9>{};
                      })
                .status,
            NumericalStatus::kOk);
  EXPECT_EQ(tracker.estimate().mean, alone.estimate().mean);
  EXPECT_EQ(tracker.estimate().covariance, alone.estimate().covariance);
  EXPECT_LT(std::abs(tracker.estimate().mean(0) - 1801.0), std::abs(start.mean(0) - 1801.0));

  // A round that is positive definite as it is keeps its indefinite increment.
  GaussianState<9> confident = prior();
  confident.covariance(2, 2) = 0.01;
  PeerTracker<TdoaRelativeMotion> sure(model, confident);
  refused.clear();
  ASSERT_EQ(fuse_tdoa_round(
                round, sure, ids.size(),
                [&](std::size_t i) {
                  return PeerSlot<9>{&increments[i], &confident};
                },
                [&](std::size_t i) { refused.push_back(i); })
                .status,
            NumericalStatus::kOk);
  EXPECT_TRUE(refused.empty());
  EXPECT_EQ(round.contributors().size(), 2U);
}

// The tree exchange's sums (stations 1-4 in clusters of 2, station 2's increment indefinite)
// give a peer the bits the in-process tree gives from the slots, the fallback included: the
// round is not positive definite, and both fuse it without station 2.
TEST(TdoaRound, TheTreesSumsAndTheirFallbackGiveTheBitsOfTheRoundsSlots) {
  const TdoaRelativeMotion model(0.002, {0.1});
  GaussianState<9> start = prior();
  start.covariance(2, 2) = 1e12;  // cannot absorb -W
  const auto indefinite =
      tdoa_increment(2, pseudo_linear_tdoa_row(Vector<2>(200.0, 0.0), 0.1, 0.1, 0.4),
                     BiasCompensation::kCompensated);
  std::vector<InformationIncrement<9>> increments(4);
  for (int i : {0, 2, 3}) {
    increments[i].station_id = i + 1;
    increments[i].delta_information(i % 2, i % 2) = 1.5 + i;
    increments[i].delta_vector(i % 2) = (1.5 + i) * 1801.0;
  }
  increments[1] = indefinite;
  const std::vector<int> ids = {1, 2, 3, 4};
  const std::vector<double> weights = {1.0, 0.5, 0.75, 1.0};
  const auto slot_at = [&](std::size_t i) { return PeerSlot<9>{&increments[i], &start}; };

  PeerTracker<TdoaRelativeMotion> twin(model, start);
  PeerRound<TdoaRelativeMotion> twin_round(ids, weights, 2);
  std::vector<int> twin_refused;
  ASSERT_EQ(fuse_tdoa_round(twin_round, twin, ids.size(), slot_at,
                            [&](std::size_t i) { twin_refused.push_back(ids[i]); })
                .status,
            NumericalStatus::kOk);
  ASSERT_EQ(twin_refused, std::vector<int>{2});

  // The aggregators' sums, added in cluster order, and the total fused.
  PeerTracker<TdoaRelativeMotion> peer(model, start);
  PeerRound<TdoaRelativeMotion> peer_round(ids, weights, 2);
  TdoaPartialSum<9> cluster;
  TdoaPartialSum<9> total;
  total.clear();
  for (std::size_t c = 0; c < 2; ++c) {
    peer_round.sum_cluster(c, slot_at, cluster);
    EXPECT_EQ(check_sum_values(cluster), std::nullopt) << "cluster " << c;
    total.add(cluster);
  }
  EXPECT_EQ(total.contributors, ids);
  EXPECT_EQ(total.definite.contributors, (std::vector<int>{1, 3, 4}));
  std::vector<int> refused;
  ASSERT_EQ(fuse_tdoa_total(peer_round, peer, total, [&](int id) { refused.push_back(id); }).status,
            NumericalStatus::kOk);
  EXPECT_EQ(refused, twin_refused);
  EXPECT_EQ(peer.estimate().mean, twin.estimate().mean);
  EXPECT_EQ(peer.estimate().covariance, twin.estimate().covariance);
  EXPECT_EQ(std::vector<int>(peer_round.contributors().begin(), peer_round.contributors().end()),
            (std::vector<int>{1, 3, 4}));

  // What a receiver refuses of such a sum: a fallback with a station the sum has not, or on
  // another reference than its first contributor's.
  TdoaPartialSum<9> forged = total;
  forged.definite.contributors = {1, 3, 5};
  EXPECT_EQ(check_sum_values(forged), DropKind::kOutOfRange);
  forged = total;
  forged.definite.reference.mean(0) += 1.0;
  EXPECT_EQ(check_sum_values(forged), DropKind::kOutOfRange);
  forged = total;
  forged.definite.sum = indefinite;
  forged.definite.sum.station_id = 1;
  EXPECT_EQ(check_sum_values(forged), DropKind::kNotPositive) << "an indefinite fallback";
  forged = total;
  forged.sum.delta_information(8, 8) = 1.0;
  EXPECT_EQ(check_sum_values(forged), DropKind::kOutOfRange) << "outside [dx, dy, d_t1]";
}

}  // namespace
}  // namespace skyfuse
