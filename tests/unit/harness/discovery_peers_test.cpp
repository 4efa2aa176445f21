// `--discovery peers`: whom each process lists, and so whom it comes to know. A member knows
// its cluster and the center, not the other clusters' members; every pair that exchanges
// samples knows each other.
#include "run/discovery_peers.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <set>
#include <vector>

namespace skyfuse::harness {
namespace {

ExchangeConfig tree(int fanout) {
  ExchangeConfig exchange;
  exchange.kind = ExchangeConfig::Kind::kTree;
  exchange.fanout = fanout;
  return exchange;
}

// Each process's known set (the lists closed under "lists or is listed by"), the harness not
// counted: what `participants_known` in its status should say once discovery is over.
std::vector<std::size_t> participants_to_know(
    const std::vector<std::vector<std::size_t>>& peer_lists) {
  std::vector<std::set<std::size_t>> known(peer_lists.size());
  for (std::size_t p = 0; p < peer_lists.size(); ++p) {
    for (std::size_t q : peer_lists[p]) {
      known[p].insert(q);
      known[q].insert(p);
    }
  }
  std::vector<std::size_t> counts;
  for (const auto& set : known) counts.push_back(set.size());
  return counts;
}

bool lists(const std::vector<std::vector<std::size_t>>& peer_lists, std::size_t a, std::size_t b) {
  const auto& list = peer_lists[a];
  return std::find(list.begin(), list.end(), b) != list.end();
}

// Whether a and b come to know each other: one of them lists the other.
bool meet(const std::vector<std::vector<std::size_t>>& peer_lists, std::size_t a, std::size_t b) {
  return lists(peer_lists, a, b) || lists(peer_lists, b, a);
}

TEST(DiscoveryPeers, TreeMembersKnowTheirClusterAndTheCenterOnly) {
  // M = 64 in clusters of 8: station j is process 1 + j.
  const auto peer_lists = discovery_peer_lists(tree(8), 64);
  ASSERT_EQ(peer_lists.size(), 65u);
  const auto known = participants_to_know(peer_lists);
  EXPECT_EQ(known[0], 64u);  // the center: every station
  // A plain member (position 2 of cluster 0): the center and its 7 cluster mates.
  EXPECT_EQ(known[1 + 2], 8u);
  EXPECT_FALSE(meet(peer_lists, 1 + 2, 1 + 8));   // cluster 1's aggregator
  EXPECT_FALSE(meet(peer_lists, 1 + 2, 1 + 10));  // cluster 1's third member
  // An aggregator and its stand-in: the center, 7 mates and 2 of each of the 7 other clusters.
  EXPECT_EQ(known[1 + 0], 1u + 7u + 14u);
  EXPECT_EQ(known[1 + 1], 1u + 7u + 14u);
}

TEST(DiscoveryPeers, EveryPairThatExchangesSamplesMeets) {
  for (const int fanout : {2, 3, 4, 8, 16}) {
    const std::size_t stations = 37;  // a last cluster smaller than the others
    const auto peer_lists = discovery_peer_lists(tree(fanout), stations);
    const auto f = static_cast<std::size_t>(fanout);
    for (std::size_t a = 0; a < stations; ++a) {
      EXPECT_TRUE(meet(peer_lists, 0, 1 + a)) << "center and station " << a;
      for (std::size_t b = a + 1; b < stations; ++b) {
        const bool same_cluster = a / f == b / f;
        const bool stand_ins = a % f < kAggregatorStandIns && b % f < kAggregatorStandIns;
        EXPECT_EQ(meet(peer_lists, 1 + a, 1 + b), same_cluster || stand_ins)
            << "fanout " << fanout << ", stations at " << a << " and " << b;
      }
    }
  }
}

TEST(DiscoveryPeers, FlatStationsKnowEveryStation) {
  ExchangeConfig flat;
  flat.kind = ExchangeConfig::Kind::kFlat;
  const auto known = participants_to_know(discovery_peer_lists(flat, 6));
  EXPECT_EQ(known, (std::vector<std::size_t>(7, 6)));
}

TEST(DiscoveryPeers, AStationListsNobodyTwiceNorItself) {
  const auto peer_lists = discovery_peer_lists(tree(4), 16);
  for (std::size_t p = 0; p < peer_lists.size(); ++p) {
    std::vector<std::size_t> sorted = peer_lists[p];
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end()) << p;
    EXPECT_EQ(std::count(sorted.begin(), sorted.end(), p), 0) << p;
  }
}

// `--stations-per-process K`: stations in ascending id, K to a process after the center.
TEST(StationGroups, CutTheAscendingIdsIntoProcessesOfK) {
  const StationGroups groups(10, 4);
  EXPECT_EQ(groups.processes(), 1u + 3u);  // the center, then 4 + 4 + 2 stations
  EXPECT_EQ(groups.process_of(0), 1u);
  EXPECT_EQ(groups.process_of(3), 1u);
  EXPECT_EQ(groups.process_of(4), 2u);
  EXPECT_EQ(groups.process_of(9), 3u);
  const std::vector<int> ids{2, 3, 5, 7, 11, 13, 17, 19, 23, 29};
  EXPECT_EQ(groups.ids_of(2, ids), (std::vector<int>{11, 13, 17, 19}));
  EXPECT_EQ(groups.ids_of(3, ids), (std::vector<int>{23, 29}));
  EXPECT_EQ(StationGroups(10, 1).processes(), 11u);  // one process per station
}

TEST(DiscoveryPeers, GroupedProcessesListTheProcessesOfTheirStationsPeers) {
  // M = 64 in clusters of 8, one cluster per process: each process holds an aggregator and its
  // stand-in, which meet every other cluster's, so every process lists every other one.
  const auto by_cluster = discovery_peer_lists(tree(8), 64, StationGroups(64, 8));
  ASSERT_EQ(by_cluster.size(), 9u);
  EXPECT_EQ(participants_to_know(by_cluster), (std::vector<std::size_t>(9, 8)));
  // Clusters of 8 in processes of 4: the second half of a cluster holds no stand-in, so it
  // meets its cluster's first half and the center only.
  const auto halves = discovery_peer_lists(tree(8), 64, StationGroups(64, 4));
  ASSERT_EQ(halves.size(), 17u);
  EXPECT_TRUE(meet(halves, 1, 2));   // cluster 0's halves
  EXPECT_TRUE(meet(halves, 1, 3));   // cluster 0's stand-ins and cluster 1's
  EXPECT_FALSE(meet(halves, 2, 3));  // cluster 0's second half, cluster 1's first
  EXPECT_FALSE(meet(halves, 2, 4));  // the second halves of clusters 0 and 1
  EXPECT_TRUE(meet(halves, 0, 16));  // the center and the last process
  for (std::size_t p = 0; p < halves.size(); ++p) {
    EXPECT_EQ(std::count(halves[p].begin(), halves[p].end(), p), 0) << p;
  }
  // K = 1 lists exactly what one process per station does.
  EXPECT_EQ(discovery_peer_lists(tree(8), 64, StationGroups(64, 1)),
            discovery_peer_lists(tree(8), 64));
}

}  // namespace
}  // namespace skyfuse::harness
