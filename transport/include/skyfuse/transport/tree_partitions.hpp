#pragma once
/// \file
/// The DDS partitions of the tree exchange (stations/tree_exchange.hpp). A writer matches only
/// the readers of its partitions, so a round's samples reach only the stations that need them:
/// a member's contribution its cluster's aggregator, an aggregator's cluster sum the other
/// aggregators, a round's total the aggregator's members. With multicast discovery every
/// station still discovers every other participant and matches, and hears, only these; with
/// `--discovery peers` (harness/run/discovery_peers.hpp) it discovers only these.

#include <fmt/format.h>

#include <cstddef>
#include <string>

namespace skyfuse::transport {

/// Members of cluster c -> its aggregator: their contributions.
inline std::string cluster_up_partition(std::size_t cluster) {
  return fmt::format("skyfuse-cluster-{}-up", cluster);
}
/// The aggregator of cluster c -> its members: the round's total.
inline std::string cluster_down_partition(std::size_t cluster) {
  return fmt::format("skyfuse-cluster-{}-down", cluster);
}
/// Every cluster's up partition, as a pattern (DDS-Security's permissions match partitions by
/// pattern).
inline constexpr const char* kEveryClusterUpPattern = "skyfuse-cluster-*-up";
/// Aggregator -> every aggregator: the clusters' sums.
inline constexpr const char* kAggregatorsPartition = "skyfuse-aggregators";

}  // namespace skyfuse::transport
