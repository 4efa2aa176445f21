// A tree exchange's sums as a receiver checks them: nothing counted twice (a station repeated
// in a sum, or in two sums), nothing outside the cluster the sum claims, and the numbers of an
// increment and a prior; a true aggregator's sum passes.
#include "skyfuse/validation/partial_sum_checks.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

namespace skyfuse {
namespace {

const std::vector<int> kIds = {1, 2, 3, 5, 8, 13, 21};  // clusters of 3: {1,2,3} {5,8,13} {21}

GaussianState<6> prior() {
  return {Vector<6>::Ones(), Covariance<6>::Identity() * 4.0};
}

// An honest sum of `ids`: each adds a positive semi-definite increment of its own.
PartialSum<6> sum_of(const std::vector<int>& ids) {
  PartialSum<6> sum;
  sum.clear();
  for (int id : ids) {
    InformationIncrement<6> increment;
    increment.station_id = id;
    increment.delta_information.topLeftCorner<3, 3>() = Covariance<3>::Identity() * id;
    increment.delta_vector.head<3>().setConstant(0.5 * id);
    sum.add(id, 1.0, increment, prior());
  }
  return sum;
}

TEST(PartialSumChecks, AnAggregatorsHonestSumPasses) {
  const ClusterLayout layout(kIds, 3);
  EXPECT_EQ(check_cluster_sum(sum_of({5, 13}), layout, 1), std::nullopt);
  EXPECT_EQ(check_cluster_sum(sum_of({}), layout, 2), std::nullopt) << "nothing arrived";
  EXPECT_EQ(check_round_total(sum_of({1, 2, 5, 21}), kIds), std::nullopt);
}

TEST(PartialSumChecks, RefusesAStationOutsideTheClusterOrTheRun) {
  const ClusterLayout layout(kIds, 3);
  EXPECT_EQ(check_cluster_sum(sum_of({5, 21}), layout, 1), DropKind::kWrongCluster);
  EXPECT_EQ(check_cluster_sum(sum_of({1}), layout, 1), DropKind::kWrongCluster);
  EXPECT_EQ(check_cluster_sum(sum_of({1}), layout, 3), DropKind::kWrongCluster) << "no cluster 3";
  EXPECT_EQ(check_round_total(sum_of({1, 4}), kIds), DropKind::kWrongCluster);
}

TEST(PartialSumChecks, RefusesAStationCountedTwice) {
  const ClusterLayout layout(kIds, 3);
  PartialSum<6> twice = sum_of({5, 8});
  twice.contributors = {5, 5};
  EXPECT_EQ(check_cluster_sum(twice, layout, 1), DropKind::kOverlap);
  twice.contributors = {8, 5};
  EXPECT_EQ(check_cluster_sum(twice, layout, 1), DropKind::kOutOfRange);
  EXPECT_TRUE(contributors_overlap(std::vector{1, 3, 5}, std::vector{2, 5}));
  EXPECT_FALSE(contributors_overlap(std::vector{1, 3}, std::vector{2, 5}));
  EXPECT_FALSE(contributors_overlap(std::vector<int>{}, std::vector{2}));
}

TEST(PartialSumChecks, RefusesNumbersNoHonestSumHas) {
  const ClusterLayout layout(kIds, 3);
  PartialSum<6> sum = sum_of({1, 2});
  sum.sum.delta_vector(0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(check_cluster_sum(sum, layout, 0), DropKind::kNonFinite);

  sum = sum_of({1, 2});
  sum.sum.delta_information(0, 0) = -50.0;  // indefinite: no sum of increments is
  EXPECT_EQ(check_cluster_sum(sum, layout, 0), DropKind::kNotPositive);

  sum = sum_of({1, 2});
  sum.reference.covariance(1, 1) = -1.0;
  EXPECT_EQ(check_cluster_sum(sum, layout, 0), DropKind::kNotPositive);

  sum = sum_of({1, 2});
  sum.sum.station_id = 2;  // not its lowest contributor
  EXPECT_EQ(check_cluster_sum(sum, layout, 0), DropKind::kOutOfRange);

  PartialSum<6> empty = sum_of({});
  empty.sum.delta_vector(2) = 1.0;  // says it counts nobody, yet adds information
  EXPECT_EQ(check_cluster_sum(empty, layout, 0), DropKind::kOutOfRange);
}

}  // namespace
}  // namespace skyfuse
