#pragma once
// What the rogue forges against the tree exchange (stations/tree_exchange.hpp): on each of the
// exchange's three channels - a member's contribution to its aggregator, an aggregator's cluster
// sum to the others, a total to a cluster's members - one partial sum of every malformed kind
// its receivers check for, each well-formed but for its one fault.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "skyfuse/tracking/cluster_layout.hpp"
#include "skyfuse/transport/topics.hpp"
#include "skyfuse/validation/drop_kind.hpp"

namespace skyfuse::rogue {

/// One forged partial sum and the DDS partition it is written in.
struct PartialAttack {
  std::string partition;
  DropKind kind;
  wire::PartialSum sample;
};

/// The partitions the attacks are written in: cluster 0's way up and way down, and the
/// aggregators'.
std::vector<std::string> partial_attack_partitions();

/// The attacks when the run ticks step k (>= 1) of run `run`, on a layout of at least two
/// clusters, for a state of `state_dim` entries. The contributions impersonate cluster 0's
/// second member, the sums cluster 1's aggregator, the totals cluster 0's aggregator.
std::vector<PartialAttack> partial_attacks_at(std::uint64_t run, std::uint32_t k,
                                              const ClusterLayout& layout, int state_dim);

/// How many receivers each partition's attacks reach: 1 (cluster 0's aggregator), the number
/// of clusters, and cluster 0's members less its aggregator.
int receivers_of(const std::string& partition, const ClusterLayout& layout);

}  // namespace skyfuse::rogue
