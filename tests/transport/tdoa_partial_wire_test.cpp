// An NCRKF's sum in the tree exchange crosses the wire as two samples, of all increments and of
// the definite ones, assembled back bit for bit only from one writer's pair.
#include "skyfuse/transport/tdoa_partial_wire.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "support/random_problems.hpp"

namespace skyfuse::transport {
namespace {

using test::random_state;
constexpr int kDim = PseudoLinearTdoaRow::kDim;

// Stands in for a DDS writer: keeps what is written, in order.
struct Written {
  std::vector<wire::PartialSum> samples;
  void write(const wire::PartialSum& sample) { samples.push_back(sample); }
};

// Stations 4 and 7, station 7's increment indefinite: the fallback holds station 4 alone.
TdoaPartialSum<kDim> two_stations(std::mt19937& rng) {
  TdoaPartialSum<kDim> sum;
  sum.clear();
  InformationIncrement<kDim> definite;
  definite.station_id = 4;
  definite.delta_information.topLeftCorner<3, 3>() = test::random_spd<3>(rng, 0.1, 2.0);
  definite.delta_vector.head<3>() = Vector3(1.0, 2.0, 3.0);
  InformationIncrement<kDim> indefinite = definite;
  indefinite.station_id = 7;
  indefinite.delta_information(2, 2) = -50.0;
  sum.add(4, 1.0, definite, random_state<kDim>(rng));
  sum.add(7, 0.5, indefinite, random_state<kDim>(rng));
  return sum;
}

constexpr WriterId kWriter{1};

TEST(TdoaPartialWire, ASumAndItsFallbackArriveAsSentOnceBothSamplesDid) {
  std::mt19937 rng(11);
  const TdoaPartialSum<kDim> sent = two_stations(rng);
  ASSERT_EQ(sent.definite.contributors, std::vector<int>{4});
  Written out;
  write_sum(out, sent, {5, 6, 4, wire::CLUSTER_SUM, 1});
  ASSERT_EQ(out.samples.size(), 2u);

  SumAssembler<TdoaPartialSum<kDim>> assembler;
  std::optional<DropKind> why;
  EXPECT_EQ(assembler.feed(out.samples[0], kWriter, why), nullptr);
  EXPECT_EQ(why, std::nullopt);
  const TdoaPartialSum<kDim>* back = assembler.feed(out.samples[1], kWriter, why);
  ASSERT_NE(back, nullptr);
  EXPECT_EQ(back->contributors, sent.contributors);
  EXPECT_EQ(back->sum.delta_information, sent.sum.delta_information);
  EXPECT_EQ(back->reference.covariance, sent.reference.covariance);
  EXPECT_EQ(back->definite.contributors, sent.definite.contributors);
  EXPECT_EQ(back->definite.sum.delta_vector, sent.definite.sum.delta_vector);
  EXPECT_EQ(check_sum_values(*back), std::nullopt);

  // A fallback with no sum before it, or one of another round: refused.
  EXPECT_EQ(assembler.feed(out.samples[1], kWriter, why), nullptr);
  EXPECT_EQ(why, DropKind::kOutOfRange);
  wire::PartialSum other_round = out.samples[1];
  other_round.step(7);
  EXPECT_EQ(assembler.feed(out.samples[0], kWriter, why), nullptr);
  EXPECT_EQ(assembler.feed(other_round, kWriter, why), nullptr);
  EXPECT_EQ(why, DropKind::kOutOfRange);
  // An IMM's fields on it: refused.
  wire::PartialSum with_terms = out.samples[0];
  with_terms.measurement_dim(3);
  EXPECT_EQ(assembler.feed(with_terms, kWriter, why), nullptr);
  EXPECT_EQ(why, DropKind::kOutOfRange);
}

}  // namespace
}  // namespace skyfuse::transport
