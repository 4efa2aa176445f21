// The center's fixed-lag re-fusion: a late measurement within the lag is stacked again into
// the round it belongs to, so the center that got it late holds the bits of one that got it in
// time; without a lag it is refused as stale; with nothing late, a lag changes no bit; and a
// measurement that arrives after the last round still enters the settled rounds.
#include "skyfuse/tracking/fixed_lag_center.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "skyfuse/models/constant_acceleration.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/tracking/round_rule.hpp"

namespace skyfuse {
namespace {

using Model = ConstantAcceleration3D;
using Sensor = RangeAzimuthElevation<9>;
using Observation = StationObservation<Sensor>;

const Model kMotion(0.02, {0.5, 0.1, 0.05});
const std::vector<int> kIds = {1, 2, 3};

GaussianState<9> initial() {
  GaussianState<9> s;
  s.mean << 0.0, 0.0, 400.0, 30.0, 5.0, 0.0, 0.0, 0.0, 0.0;
  s.covariance = Covariance<9>::Identity() * 25.0;
  return s;
}

// The stacked EKF, as the center runs it for the `ekf` part.
class StackedEkf {
 public:
  using State = GaussianState<9>;
  static constexpr bool kRefuses = true;

  StackedEkf() : tracker_(kMotion, initial()), round_(kIds.size()) {}
  template <typename ObservationAt, typename OnRefused>
  NumericalStatus update(std::size_t count, ObservationAt observation_at, const NisGate& gate,
                         OnRefused on_refused) {
    return round_.update(tracker_, count, observation_at, gate, on_refused).status;
  }
  void predict() { tracker_.predict(); }
  const State& state() const { return tracker_.estimate(); }
  void reset_to(const State& state) { tracker_.reset_to(state); }

 private:
  CentralTracker<Model, Sensor> tracker_;
  CentralRound<Model, Sensor> round_;
};

// Station `id`'s measurement of round k: the truth (a straight flight) seen from its site, with
// a fixed offset that differs by station and round, so every measurement moves the estimate.
Observation measurement(int id, std::uint64_t k) {
  const Vector3 sites[] = {{-800.0, 100.0, 20.0}, {600.0, -700.0, 30.0}, {300.0, 900.0, 10.0}};
  Vector<9> truth = initial().mean;
  truth.head<3>() += truth.segment<3>(3) * (0.02 * static_cast<double>(k));
  Observation o;
  o.station_id = id;
  o.sensor = Sensor(sites[id - 1]);
  o.noise = Vector3(0.5 * 0.5, 1e-6, 1e-6).asDiagonal();
  o.z = o.sensor.predict(truth);
  o.z(Sensor::kRange) += 0.1 * static_cast<double>((id * 7 + static_cast<int>(k)) % 5) - 0.2;
  return o;
}

enum class Late { kNone, kDelivered, kAfterTheLastRound };

struct Outcome {
  std::vector<GaussianState<9>> final_posteriors;  // by round, as each last left the chain
  std::uint64_t late_used = 0;
  int refused = 0;
};

// Runs rounds 0..steps-1 with lag `lag`; station 3's measurement of `late_round` comes two
// rounds late (kDelivered), or after the last round (kAfterTheLastRound).
Outcome run(std::size_t lag, Late late, std::uint64_t late_round = 3, std::uint64_t steps = 6) {
  FixedLagCenter<StackedEkf, Observation> center(StackedEkf{}, kIds, lag);
  Outcome out;
  out.final_posteriors.resize(steps);
  const auto on_updated = [&](std::uint64_t q) {
    out.final_posteriors[q] = center.fusion().state();
  };
  const auto offer_late = [&] {
    const auto why = center.collector().offer(late_round, 3, measurement(3, late_round));
    if (why) {
      EXPECT_EQ(why, DropKind::kStaleStep);
    } else {
      center.kept(late_round);
    }
  };
  const NisGate gate;
  for (std::uint64_t k = 0; k < steps; ++k) {
    if (late == Late::kDelivered && k == late_round + 2) offer_late();
    for (int id : kIds) {
      if (id == 3 && k == late_round && late != Late::kNone) continue;
      EXPECT_EQ(center.collector().offer(k, id, measurement(id, k)), std::nullopt);
      center.kept(k);
    }
    EXPECT_EQ(center.close_round(
                  gate, [&](int, DropKind) { ++out.refused; }, on_updated),
              NumericalStatus::kOk);
    center.advance();
  }
  if (late == Late::kAfterTheLastRound) offer_late();
  NumericalStatus status;
  const auto [from, to] = center.settle_rest(gate, on_updated, status);
  EXPECT_EQ(status, NumericalStatus::kOk);
  EXPECT_EQ(to, steps);
  EXPECT_EQ(from, lag == 0 ? steps : steps - lag);
  out.late_used = center.late_used();
  return out;
}

bool same_bits(const GaussianState<9>& a, const GaussianState<9>& b) {
  return std::memcmp(a.mean.data(), b.mean.data(), sizeof(double) * 9) == 0 &&
         std::memcmp(a.covariance.data(), b.covariance.data(), sizeof(double) * 81) == 0;
}

void expect_same_rounds(const Outcome& a, const Outcome& b) {
  ASSERT_EQ(a.final_posteriors.size(), b.final_posteriors.size());
  for (std::size_t q = 0; q < a.final_posteriors.size(); ++q) {
    EXPECT_TRUE(same_bits(a.final_posteriors[q], b.final_posteriors[q])) << "round " << q;
  }
}

TEST(FixedLagCenter, ALateMeasurementWithinTheLagGivesTheBitsOfOneInTime) {
  const Outcome in_time = run(0, Late::kNone);
  const Outcome late = run(3, Late::kDelivered);
  EXPECT_EQ(late.late_used, 1u);
  expect_same_rounds(late, in_time);
}

TEST(FixedLagCenter, WithoutALagALateMeasurementIsRefusedAsStaleAndLost) {
  const Outcome in_time = run(0, Late::kNone);
  const Outcome late = run(0, Late::kDelivered);
  EXPECT_EQ(late.late_used, 0u);
  EXPECT_TRUE(same_bits(late.final_posteriors[2], in_time.final_posteriors[2]));
  EXPECT_FALSE(same_bits(late.final_posteriors[3], in_time.final_posteriors[3]));
  EXPECT_FALSE(same_bits(late.final_posteriors[5], in_time.final_posteriors[5]));
}

TEST(FixedLagCenter, WithNothingLateALagChangesNoBit) {
  const Outcome without = run(0, Late::kNone);
  const Outcome with = run(4, Late::kNone);
  EXPECT_EQ(with.late_used, 0u);
  expect_same_rounds(with, without);
}

TEST(FixedLagCenter, AMeasurementOfTheLastRoundThatArrivesAfterItClosedEntersTheSettledTrack) {
  const Outcome in_time = run(0, Late::kNone);
  const Outcome late = run(3, Late::kAfterTheLastRound, 5);
  EXPECT_EQ(late.late_used, 1u);
  expect_same_rounds(late, in_time);
}

TEST(FixedLagCenter, ARefusedMeasurementIsToldOnceWhenItsRoundClosesNotWhenItIsUpdatedAgain) {
  // Station 2's range of every round is 10 km off: the gate screens it out each round. Station
  // 3's late measurement makes the center update two rounds again; the refusals stay one a round.
  FixedLagCenter<StackedEkf, Observation> center(StackedEkf{}, kIds, 3);
  const NisGate gate = NisGate::at_probability(0.9999);
  int refused = 0;
  for (std::uint64_t k = 0; k < 4; ++k) {
    if (k == 3) {
      ASSERT_EQ(center.collector().offer(1, 3, measurement(3, 1)), std::nullopt);
      center.kept(1);
    }
    for (int id : kIds) {
      if (id == 3 && k == 1) continue;
      Observation o = measurement(id, k);
      if (id == 2) o.z(Sensor::kRange) += 10'000.0;
      ASSERT_EQ(center.collector().offer(k, id, o), std::nullopt);
    }
    ASSERT_EQ(center.close_round(
                  gate,
                  [&](int station_id, DropKind why) {
                    EXPECT_EQ(station_id, 2);
                    EXPECT_EQ(why, DropKind::kNisGate);
                    ++refused;
                  },
                  [](std::uint64_t) {}),
              NumericalStatus::kOk);
    if (k < 3) center.advance();
  }
  EXPECT_EQ(refused, 4);
}

}  // namespace
}  // namespace skyfuse
