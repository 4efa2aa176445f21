#include "run/discovery_peers.hpp"

#include <algorithm>
#include <set>

#include "skyfuse/tracking/cluster_layout.hpp"

namespace skyfuse::harness {

namespace {

constexpr std::size_t kCenter = 0;
std::size_t process_of_station(std::size_t position) {
  return 1 + position;
}

}  // namespace

std::vector<std::vector<std::size_t>> discovery_peer_lists(const ExchangeConfig& exchange,
                                                           std::size_t stations) {
  std::vector<std::vector<std::size_t>> lists(1 + stations);
  for (std::size_t j = 0; j < stations; ++j) {
    lists[kCenter].push_back(process_of_station(j));
    lists[process_of_station(j)].push_back(kCenter);
  }
  // Positions stand in for ids: the layout cuts the ascending ids at the same positions.
  std::vector<int> positions(stations);
  for (std::size_t j = 0; j < stations; ++j) positions[j] = static_cast<int>(j);
  const std::size_t fanout = exchange.round_fanout() == 0 ? stations : exchange.round_fanout();
  const ClusterLayout layout(positions, std::max<std::size_t>(fanout, 1));
  const auto stand_in = [&](std::size_t j) {
    return j - layout.first_index(layout.cluster_of_index(j)) < kAggregatorStandIns;
  };
  for (std::size_t j = 0; j < stations; ++j) {
    std::vector<std::size_t>& list = lists[process_of_station(j)];
    const std::size_t cluster = layout.cluster_of_index(j);
    for (std::size_t other = 0; other < stations; ++other) {
      if (other == j) continue;
      const bool same_cluster = layout.cluster_of_index(other) == cluster;
      if (same_cluster || (stand_in(j) && stand_in(other))) {
        list.push_back(process_of_station(other));
      }
    }
  }
  return lists;
}

std::vector<std::vector<std::size_t>> discovery_peer_lists(const ExchangeConfig& exchange,
                                                           std::size_t stations,
                                                           const StationGroups& groups) {
  const std::vector<std::vector<std::size_t>> by_station = discovery_peer_lists(exchange, stations);
  const auto process_of = [&](std::size_t station_process) {
    return station_process == kCenter ? kCenter : groups.process_of(station_process - 1);
  };
  std::vector<std::set<std::size_t>> merged(groups.processes());
  for (std::size_t p = 0; p < by_station.size(); ++p) {
    for (std::size_t peer : by_station[p]) merged[process_of(p)].insert(process_of(peer));
  }
  std::vector<std::vector<std::size_t>> lists(merged.size());
  for (std::size_t p = 0; p < merged.size(); ++p) {
    merged[p].erase(p);
    lists[p].assign(merged[p].begin(), merged[p].end());
  }
  return lists;
}

}  // namespace skyfuse::harness
