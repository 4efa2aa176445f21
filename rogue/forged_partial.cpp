#include "forged_partial.hpp"

#include <cmath>

#include "fault_step.hpp"
#include "skyfuse/transport/tree_partitions.hpp"
#include "skyfuse/transport/wire_conversion.hpp"

namespace skyfuse::rogue {
namespace {

// A sum over `contributors` of a range-like information of 1e-4 along x about a prior with mean
// 0 and P = I: passes every check of a sum's values.
wire::PartialSum plausible_partial(std::uint64_t run, std::uint32_t step, int sender,
                                   wire::SumKind kind, std::uint32_t cluster,
                                   const std::vector<std::int32_t>& contributors, int state_dim) {
  Eigen::MatrixXd information = Eigen::MatrixXd::Zero(state_dim, state_dim);
  information(0, 0) = 1e-4;
  const auto n = static_cast<std::size_t>(state_dim);
  wire::PartialSum s;
  s.run_id(run);
  s.step(step);
  s.station_id(sender);
  s.kind(kind);
  s.cluster(cluster);
  s.contributors(contributors);
  s.delta_information(transport::pack_upper<Eigen::Dynamic>(information));
  s.delta_vector(std::vector<double>(n, 0.0));
  s.prior_x(std::vector<double>(n, 0.0));
  s.prior_covariance(
      transport::pack_upper<Eigen::Dynamic>(Eigen::MatrixXd::Identity(state_dim, state_dim)));
  return s;
}

// The kinds every channel is attacked with (the step each names: fault_step.hpp). The one whose
// kind depends on timing goes first, as in rogue_node.cpp.
constexpr DropKind kEveryChannel[] = {
    DropKind::kDuplicate, DropKind::kWrongRun,    DropKind::kStaleStep,   DropKind::kFutureStep,
    DropKind::kNonFinite, DropKind::kNotPositive, DropKind::kWrongCluster};

// What a channel's forged sample looks like when well formed, and its wrong-cluster variant.
struct Channel {
  std::string partition;
  wire::SumKind kind;
  std::uint32_t cluster;
  int sender;
  std::vector<std::int32_t> contributors;
  int wrong_sender;                              // for kWrongCluster, if not the sender
  std::vector<std::int32_t> wrong_contributors;  // for kWrongCluster, if not the contributors
  bool takes_overlap;                            // a sum of several stations, not a contribution
};

std::vector<Channel> channels(const ClusterLayout& layout) {
  const auto c0 = layout.members(0);
  const auto c1 = layout.members(1);
  return {
      // A member's contribution, from cluster 0's second member; wrong: from cluster 1.
      {transport::cluster_up_partition(0), wire::CONTRIBUTION, 0, c0[1], {c0[1]}, c1[0], {}, false},
      // Cluster 1's sum from its aggregator; wrong: counting a station of cluster 0.
      {transport::kAggregatorsPartition,
       wire::CLUSTER_SUM,
       1,
       c1[0],
       {c1[0]},
       c1[0],
       {c0.back(), c1[0]},
       true},
      // Cluster 0's total from its aggregator; wrong: from one of its members.
      {transport::cluster_down_partition(0), wire::ROUND_TOTAL, 0, c0[0], {c0[0]}, c0[1], {}, true},
  };
}

}  // namespace

std::vector<std::string> partial_attack_partitions() {
  return {transport::cluster_up_partition(0), transport::kAggregatorsPartition,
          transport::cluster_down_partition(0)};
}

std::vector<PartialAttack> partial_attacks_at(std::uint64_t run, std::uint32_t k,
                                              const ClusterLayout& layout, int state_dim) {
  std::vector<PartialAttack> attacks;
  for (const Channel& c : channels(layout)) {
    auto forge = [&](DropKind kind) {
      const bool wrong = kind == DropKind::kWrongCluster;
      const int sender = wrong ? c.wrong_sender : c.sender;
      std::vector<std::int32_t> contributors = c.contributors;
      if (wrong) {
        contributors =
            c.wrong_contributors.empty() ? std::vector<std::int32_t>{sender} : c.wrong_contributors;
      }
      if (kind == DropKind::kOverlap) contributors = {c.contributors[0], c.contributors[0]};
      const std::uint64_t run_id = kind == DropKind::kWrongRun ? run ^ 0x5a5a5a5aULL : run;
      const std::uint32_t step = fault_step(kind, k);
      wire::PartialSum s =
          plausible_partial(run_id, step, sender, c.kind, c.cluster, contributors, state_dim);
      if (kind == DropKind::kNonFinite) s.delta_information()[1] = std::nan("");
      if (kind == DropKind::kNotPositive) s.delta_information()[0] = -1.0;
      attacks.push_back({c.partition, kind, std::move(s)});
    };
    for (const DropKind kind : kEveryChannel) forge(kind);
    if (c.takes_overlap) forge(DropKind::kOverlap);
  }
  return attacks;
}

int receivers_of(const std::string& partition, const ClusterLayout& layout) {
  if (partition == transport::kAggregatorsPartition) return static_cast<int>(layout.clusters());
  if (partition == transport::cluster_down_partition(0)) {
    return static_cast<int>(layout.members(0).size()) - 1;
  }
  return 1;
}

}  // namespace skyfuse::rogue
