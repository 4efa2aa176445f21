// An IMM's sum in the tree exchange crosses the wire as one sample per mode and is assembled
// back, bit for bit, only from one writer's modes of one sum in order; what a receiver checks of
// it (validation/partial_sum_checks.hpp).
#include "skyfuse/transport/imm_partial_wire.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "skyfuse/models/constant_acceleration.hpp"
#include "skyfuse/models/constant_velocity.hpp"
#include "skyfuse/validation/partial_sum_checks.hpp"
#include "support/random_problems.hpp"

namespace skyfuse::transport {
namespace {

using Sum = ImmPartialSum<ConstantVelocity3D, ConstantAcceleration3D>;

using test::random_state;

Sum::Contribution random_contribution(int id, std::mt19937& rng) {
  Sum::Contribution c;
  c.station_id = id;
  std::get<0>(c.modes) = {{id, test::random_spd<6>(rng, 0.1, 10.0), random_state<6>(rng).mean},
                          random_state<6>(rng)};
  std::get<1>(c.modes) = {{id, test::random_spd<9>(rng, 0.1, 10.0), random_state<9>(rng).mean},
                          random_state<9>(rng)};
  c.terms = {LikelihoodTerms{2.25, -17.5, 3}, LikelihoodTerms{1.75, -16.25, 3}};
  c.prior_probabilities = Vector<2>(0.625, 0.375);
  return c;
}

// Stands in for a DDS writer: keeps what is written, in order.
struct Written {
  std::vector<wire::PartialSum> samples;
  void write(const wire::PartialSum& sample) { samples.push_back(sample); }
};

Sum three_stations(std::mt19937& rng) {
  Sum sum;
  sum.clear();
  for (int id : {4, 7, 9}) sum.add(0.75, random_contribution(id, rng));
  return sum;
}

constexpr WriterId kWriter{1};
constexpr WriterId kOtherWriter{2};

TEST(ImmPartialWire, AnImmSumArrivesAsSentOnceItsWriterSentEveryMode) {
  std::mt19937 rng(7);
  const Sum sent = three_stations(rng);
  Written out;
  write_sum(out, sent, {5, 6, 4, wire::CLUSTER_SUM, 1});
  ASSERT_EQ(out.samples.size(), 2u);
  EXPECT_EQ(out.samples[0].mode(), 0u);
  EXPECT_EQ(out.samples[1].mode(), 1u);

  SumAssembler<Sum> assembler;
  std::optional<DropKind> why;
  EXPECT_EQ(assembler.feed(out.samples[0], kWriter, why), nullptr);
  EXPECT_EQ(why, std::nullopt) << "not refused: its second mode is still to come";
  const Sum* back = assembler.feed(out.samples[1], kWriter, why);
  ASSERT_NE(back, nullptr);
  EXPECT_EQ(back->contributors, sent.contributors);
  EXPECT_EQ(std::get<0>(back->sums).delta_information, std::get<0>(sent.sums).delta_information);
  EXPECT_EQ(std::get<1>(back->sums).delta_vector, std::get<1>(sent.sums).delta_vector);
  EXPECT_EQ(std::get<1>(back->sums).station_id, 4);
  EXPECT_EQ(std::get<1>(back->references).covariance, std::get<1>(sent.references).covariance);
  EXPECT_EQ(back->prior_probabilities, sent.prior_probabilities);
  for (int m = 0; m < 2; ++m) {
    EXPECT_EQ(back->terms[m].weighted_innovation, sent.terms[m].weighted_innovation);
    EXPECT_EQ(back->terms[m].log_det_noise, sent.terms[m].log_det_noise);
    EXPECT_EQ(back->terms[m].measurement_dim, 9);
  }
  EXPECT_EQ(check_sum_values(*back), std::nullopt);

  // A sum of nobody: no reference, no probabilities.
  Sum nobody;
  nobody.clear();
  Written empty;
  write_sum(empty, nobody, {5, 6, 1, wire::CLUSTER_SUM, 0});
  EXPECT_EQ(assembler.feed(empty.samples[0], kWriter, why), nullptr);
  const Sum* none = assembler.feed(empty.samples[1], kWriter, why);
  ASSERT_NE(none, nullptr);
  EXPECT_TRUE(none->empty());
  EXPECT_EQ(check_sum_values(*none), std::nullopt);
}

TEST(ImmPartialWire, ModesOfTwoSumsOrOutOfOrderAreRefusedNeverMixed) {
  std::mt19937 rng(8);
  const Sum sent = three_stations(rng);
  Written round6;
  Written round7;
  write_sum(round6, sent, {5, 6, 4, wire::CLUSTER_SUM, 1});
  write_sum(round7, sent, {5, 7, 4, wire::CLUSTER_SUM, 1});
  SumAssembler<Sum> assembler;
  std::optional<DropKind> why;

  EXPECT_EQ(assembler.feed(round6.samples[1], kWriter, why), nullptr);
  EXPECT_EQ(why, DropKind::kOutOfRange) << "a second mode with no first";

  EXPECT_EQ(assembler.feed(round6.samples[0], kWriter, why), nullptr);
  EXPECT_EQ(assembler.feed(round7.samples[1], kWriter, why), nullptr);
  EXPECT_EQ(why, DropKind::kOutOfRange) << "another round's second mode";
  EXPECT_EQ(assembler.feed(round6.samples[1], kWriter, why), nullptr);
  EXPECT_EQ(why, DropKind::kOutOfRange) << "the refusal dropped the incomplete sum";

  wire::PartialSum other_set = round6.samples[1];
  other_set.contributors({4, 7});
  EXPECT_EQ(assembler.feed(round6.samples[0], kWriter, why), nullptr);
  EXPECT_EQ(assembler.feed(other_set, kWriter, why), nullptr);
  EXPECT_EQ(why, DropKind::kOutOfRange) << "another contributor set";

  // A first mode again replaces an incomplete sum (its second was lost); two writers' sums
  // assemble side by side.
  EXPECT_EQ(assembler.feed(round6.samples[0], kWriter, why), nullptr);
  EXPECT_EQ(assembler.feed(round7.samples[0], kWriter, why), nullptr);
  EXPECT_EQ(assembler.feed(round6.samples[0], kOtherWriter, why), nullptr);
  EXPECT_EQ(why, std::nullopt);
  const Sum* seventh = assembler.feed(round7.samples[1], kWriter, why);
  ASSERT_NE(seventh, nullptr);
  EXPECT_EQ(seventh->contributors, sent.contributors);
  EXPECT_NE(assembler.feed(round6.samples[1], kOtherWriter, why), nullptr);

  // Mode 2 of a two-mode IMM, or a mode of another dimension: refused.
  wire::PartialSum third = round6.samples[1];
  third.mode(2);
  EXPECT_EQ(assembler.feed(third, kWriter, why), nullptr);
  EXPECT_EQ(why, DropKind::kOutOfRange);
  wire::PartialSum wrong_dim = round6.samples[1];
  wrong_dim.delta_vector(std::vector<double>(6, 0.0));
  EXPECT_EQ(assembler.feed(round6.samples[0], kWriter, why), nullptr);
  EXPECT_EQ(assembler.feed(wrong_dim, kWriter, why), nullptr);
  EXPECT_EQ(why, DropKind::kOutOfRange);
}

TEST(ImmPartialWire, ASingleModelReceiverRefusesAnImmsSum) {
  std::mt19937 rng(9);
  Written out;
  write_sum(out, three_stations(rng), {5, 6, 4, wire::CLUSTER_SUM, 1});
  SumAssembler<PartialSum<6>> single_model;
  std::optional<DropKind> why;
  EXPECT_EQ(single_model.feed(out.samples[0], kWriter, why), nullptr) << "mode 0, 6 states";
  EXPECT_EQ(why, DropKind::kOutOfRange);
}

TEST(ImmPartialWire, AReceiverChecksASumsTermsAndModeProbabilities) {
  std::mt19937 rng(10);
  const Sum good = three_stations(rng);
  ASSERT_EQ(check_sum_values(good), std::nullopt);

  Sum bad = good;
  bad.prior_probabilities = Vector<2>(0.7, 0.4);
  EXPECT_EQ(check_sum_values(bad), DropKind::kOutOfRange) << "probabilities summing to 1.1";
  bad = good;
  bad.terms[1].log_det_noise = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(check_sum_values(bad), DropKind::kNonFinite);
  bad = good;
  bad.terms[0].measurement_dim = 3 * 16 + 1;
  EXPECT_EQ(check_sum_values(bad), DropKind::kOutOfRange) << "more than 16 per contributor";
  bad = good;
  bad.terms[0].weighted_innovation = -1.0;
  EXPECT_EQ(check_sum_values(bad), DropKind::kOutOfRange);
  bad = good;
  std::get<1>(bad.sums).delta_information(0, 0) = -1e6;
  EXPECT_EQ(check_sum_values(bad), DropKind::kNotPositive);
  bad = good;
  bad.terms[1] = {};
  EXPECT_EQ(check_sum_values(bad), DropKind::kOutOfRange) << "no measurement, yet information";

  // Its contributors as for any sum: inside the cluster.
  const std::vector<int> ids = {1, 2, 3, 4, 5, 6, 7, 8, 9};
  const ClusterLayout layout(ids, 3);
  EXPECT_EQ(check_cluster_sum(good, layout, 1), DropKind::kWrongCluster) << "4, 7, 9";
  EXPECT_EQ(check_round_total(good, ids), std::nullopt);
}

}  // namespace
}  // namespace skyfuse::transport
