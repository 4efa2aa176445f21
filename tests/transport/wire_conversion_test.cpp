// Every wire conversion, there and back: the values that arrive are the values that were sent,
// bit for bit, for any sensor and state dimension; a sample of another kind or other lengths
// converts to nothing.
#include "skyfuse/transport/wire_conversion.hpp"

#include <gtest/gtest.h>

#include <random>

#include "skyfuse/models/constant_acceleration.hpp"
#include "skyfuse/models/constant_velocity.hpp"
#include "skyfuse/models/position_velocity.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/transport/imm_wire.hpp"
#include "skyfuse/transport/partial_wire.hpp"
#include "support/random_problems.hpp"

namespace skyfuse::transport {
namespace {

using test::random_state;

TEST(WireConversion, ARangeAzimuthElevationMeasurementArrivesAsSent) {
  std::mt19937 rng(1);
  StationObservation<RangeAzimuthElevation<9>> sent{
      7, RangeAzimuthElevation<9>(Vector3(-450.0, 12.5, 20.0)), Vector3(1523.25, -0.3, 0.2),
      test::random_spd<3>(rng, 1e-5, 1.0)};
  const wire::Measurement sample = to_wire(sent, 42, 9);
  EXPECT_EQ(sample.run_id(), 42U);
  EXPECT_EQ(sample.step(), 9U);
  EXPECT_STREQ(sample.sensor().c_str(), "range_azimuth_elevation");
  const auto back = observation_from_wire<RangeAzimuthElevation<9>>(sample);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->station_id, 7);
  EXPECT_EQ(back->z, sent.z);
  EXPECT_EQ(back->noise, sent.noise);
  EXPECT_EQ(back->sensor.site(), sent.sensor.site());
  // Read as another sensor: refused.
  EXPECT_FALSE(observation_from_wire<PositionVelocity<9>>(sample).has_value());
}

TEST(WireConversion, AGpsMeasurementArrivesAsSentAndOtherLengthsAreRefused) {
  std::mt19937 rng(2);
  StationObservation<PositionVelocity<6>> sent;
  sent.station_id = 11;
  sent.z << 1.0, -2.0, 3.5, 10.0, 5.0, -1.0;
  sent.noise = test::random_spd<6>(rng, 1.0, 9.0);
  wire::Measurement sample = to_wire(sent, 1, 2);
  const auto back = observation_from_wire<PositionVelocity<6>>(sample);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->z, sent.z);
  EXPECT_EQ(back->noise, sent.noise);
  EXPECT_EQ(back->sensor.site(), Vector3::Zero());
  sample.z().pop_back();
  EXPECT_FALSE(observation_from_wire<PositionVelocity<6>>(sample).has_value());
  sample = to_wire(sent, 1, 2);
  sample.noise().push_back(0.0);
  EXPECT_FALSE(observation_from_wire<PositionVelocity<6>>(sample).has_value());
}

template <int N>
void expect_increment_round_trip(std::mt19937& rng) {
  PeerContribution<N> sent;
  sent.increment.station_id = 3;
  sent.increment.delta_information = test::random_spd<N>(rng, 0.0, 10.0);
  sent.increment.delta_vector = random_state<N>(rng).mean;
  sent.prior = random_state<N>(rng);
  const wire::InformationIncrement sample = to_wire(sent, 5, 6);
  const auto back = contribution_from_wire<N>(sample);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->increment.station_id, 3);
  EXPECT_EQ(back->increment.delta_information, sent.increment.delta_information);
  EXPECT_EQ(back->increment.delta_vector, sent.increment.delta_vector);
  EXPECT_EQ(back->prior.mean, sent.prior.mean);
  EXPECT_EQ(back->prior.covariance, sent.prior.covariance);
}

TEST(WireConversion, IncrementsOfAnyStateDimensionArriveAsSent) {
  std::mt19937 rng(3);
  expect_increment_round_trip<9>(rng);
  expect_increment_round_trip<6>(rng);
  // A 6-state increment is not a 9-state one.
  PeerContribution<6> six;
  EXPECT_FALSE(contribution_from_wire<9>(to_wire(six, 1, 1)).has_value());
}

// A tree exchange's sum: its contributors, sums and reference cross bit for bit; a sum that
// counts nobody carries no reference; other lengths than the state's are not a sum of it.
TEST(WireConversion, PartialSumsArriveAsSent) {
  std::mt19937 rng(5);
  PartialSum<9> sent;
  sent.clear();
  for (int id : {4, 7, 9}) {
    InformationIncrement<9> increment;
    increment.station_id = id;
    increment.delta_information = test::random_spd<9>(rng, 0.0, 10.0);
    increment.delta_vector = random_state<9>(rng).mean;
    sent.add(id, 0.75, increment, random_state<9>(rng));
  }
  const wire::PartialSum sample = to_wire(sent, {5, 6, 4, wire::ROUND_TOTAL, 2});
  EXPECT_EQ(sample.cluster(), 2u);
  EXPECT_EQ(sample.kind(), wire::ROUND_TOTAL);
  EXPECT_EQ(sample.station_id(), 4);
  const auto back = partial_sum_from_wire<9>(sample);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->contributors, sent.contributors);
  EXPECT_EQ(back->sum.station_id, 4);
  EXPECT_EQ(back->sum.delta_information, sent.sum.delta_information);
  EXPECT_EQ(back->sum.delta_vector, sent.sum.delta_vector);
  EXPECT_EQ(back->reference.mean, sent.reference.mean);
  EXPECT_EQ(back->reference.covariance, sent.reference.covariance);

  PartialSum<9> nobody;
  nobody.clear();
  const auto empty = partial_sum_from_wire<9>(to_wire(nobody, {5, 6, 1, wire::CLUSTER_SUM, 0}));
  ASSERT_TRUE(empty.has_value());
  EXPECT_TRUE(empty->empty());
  wire::PartialSum forged = to_wire(nobody, {5, 6, 1, wire::CLUSTER_SUM, 0});
  forged.prior_x(std::vector<double>(9, 0.0));
  EXPECT_FALSE(partial_sum_from_wire<9>(forged).has_value()) << "a reference counting nobody";
  EXPECT_FALSE(partial_sum_from_wire<6>(sample).has_value());
}

TEST(WireConversion, TracksOfAnyStateDimensionArriveAsSent) {
  std::mt19937 rng(4);
  const int contributors[] = {1, 2, 11};
  const GaussianState<9> nine = random_state<9>(rng);
  const wire::TrackEstimate sample = to_wire(nine, 8, 3, 0, wire::CENTRAL, contributors);
  const auto back = estimate_from_wire<9>(sample);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->mean, nine.mean);
  EXPECT_EQ(back->covariance, nine.covariance);
  EXPECT_EQ(sample.contributors(), std::vector<int32_t>({1, 2, 11}));
  EXPECT_FALSE(estimate_from_wire<6>(sample).has_value());
  const GaussianState<6> six = random_state<6>(rng);
  const auto back6 = estimate_from_wire<6>(to_wire(six, 8, 3, 2, wire::PEER, contributors));
  ASSERT_TRUE(back6.has_value());
  EXPECT_EQ(back6->covariance, six.covariance);
}

TEST(WireConversion, AnImmContributionArrivesAsSentModeByMode) {
  std::mt19937 rng(4);
  ImmContribution<ConstantVelocity3D, ConstantAcceleration3D> sent;
  sent.station_id = 5;
  std::get<0>(sent.modes).increment = {5, test::random_spd<6>(rng, 0.1, 10.0),
                                       random_state<6>(rng).mean};
  std::get<0>(sent.modes).prior = random_state<6>(rng);
  std::get<1>(sent.modes).increment = {5, test::random_spd<9>(rng, 0.1, 10.0),
                                       random_state<9>(rng).mean};
  std::get<1>(sent.modes).prior = random_state<9>(rng);
  sent.terms = {LikelihoodTerms{2.25, -17.5, 3}, LikelihoodTerms{1.75, -17.5, 3}};
  sent.prior_probabilities = Vector<2>(0.625, 0.375);

  const wire::InformationIncrement first = mode_to_wire<0>(sent, 42, 9);
  const wire::InformationIncrement second = mode_to_wire<1>(sent, 42, 9);
  EXPECT_EQ(first.mode(), 0U);
  EXPECT_EQ(second.mode(), 1U);
  EXPECT_FALSE(is_single_model_sample(first));  // mode 0 of an IMM all the same
  const auto cv = mode_from_wire<6, 2>(first);
  const auto ca = mode_from_wire<9, 2>(second);
  ASSERT_TRUE(cv && ca);
  EXPECT_EQ(cv->contribution.increment.delta_information,
            std::get<0>(sent.modes).increment.delta_information);
  EXPECT_EQ(cv->contribution.prior.covariance, std::get<0>(sent.modes).prior.covariance);
  EXPECT_EQ(ca->contribution.increment.delta_vector,
            std::get<1>(sent.modes).increment.delta_vector);
  EXPECT_EQ(ca->terms.weighted_innovation, 1.75);
  EXPECT_EQ(ca->terms.log_det_noise, -17.5);
  EXPECT_EQ(ca->terms.measurement_dim, 3);
  EXPECT_EQ(ca->prior_probabilities, sent.prior_probabilities);

  // The other mode's dimension, another number of modes, or an impossible dimension: nothing.
  EXPECT_FALSE((mode_from_wire<9, 2>(first)));
  EXPECT_FALSE((mode_from_wire<6, 3>(first)));
  wire::InformationIncrement huge = first;
  huge.measurement_dim(1000);
  EXPECT_FALSE((mode_from_wire<6, 2>(huge)));
  // A single-model run's sample carries none of it.
  EXPECT_TRUE(is_single_model_sample(to_wire(std::get<1>(sent.modes), 42, 9)));
}

}  // namespace
}  // namespace skyfuse::transport
