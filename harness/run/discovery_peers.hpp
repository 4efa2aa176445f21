#pragma once
// `skyfuse run --discovery peers`: whom each process announces itself to. With simple
// discovery a participant learns of another only from that one's announcement, and it
// announces itself to the peers it lists and to those it has learnt of. So a process knows
// exactly the processes it lists and those that list it: list a process's exchange partners,
// and it discovers them and nobody else.
//
// Why it matters: with multicast discovery every participant knows every other one, and Fast
// DDS 2.9 resends its announcement to all it knows each time it learns of a new one, so a
// run's start costs about M^3 receptions: at M = 256 on 2 cores discovery had not finished
// after 25 minutes (docs/performance.md).
//
// Processes are numbered as the harness starts them: 0 the center, 1 + j the j-th station in
// ascending id. The harness lists every process, and every process lists the harness (ticks,
// statuses, tracks); that is not repeated in the lists below.

#include <cstddef>
#include <vector>

#include "run/station_groups.hpp"
#include "skyfuse/scenario/scenario.hpp"

namespace skyfuse::harness {

/// The members of a cluster that the other clusters' aggregators meet: the aggregator and the
/// member that takes its place when it fails. A cluster that loses both is cut off from the
/// other clusters until one of them returns.
inline constexpr std::size_t kAggregatorStandIns = 2;

/// For each of the run's 1 + `stations` processes, the processes it lists. The center lists
/// every station (it reads their measurements). With the flat exchange every station lists
/// every other one (each hears every increment). With the tree, a station lists its cluster,
/// and a cluster's first kAggregatorStandIns members also list the other clusters' first ones.
std::vector<std::vector<std::size_t>> discovery_peer_lists(const ExchangeConfig& exchange,
                                                           std::size_t stations);

/// The same for processes that run several stations each (`groups`): a process lists the
/// processes of every station its stations list, itself excepted.
std::vector<std::vector<std::size_t>> discovery_peer_lists(const ExchangeConfig& exchange,
                                                           std::size_t stations,
                                                           const StationGroups& groups);

}  // namespace skyfuse::harness
