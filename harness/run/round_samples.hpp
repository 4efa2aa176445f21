#pragma once
// What a round must carry and where its processes fit, as the scale benchmark counts them.

#include <string_view>

namespace skyfuse::harness {

/// The data samples one round must deliver with `exchange` ("flat" or "tree") at M =
/// `stations`: a tick to every node (stations and center), every measurement to the center and
/// to the harness's recorder, every node's track to the harness, and the increments — flat:
/// M (M - 1); tree, with C = ceil(M / fanout) clusters: each member's contribution to its
/// aggregator (M - C), the clusters' sums among the aggregators (C (C - 1)) and the totals
/// back to the members (M - C).
constexpr long samples_per_round(std::string_view exchange, int stations, int fanout) {
  const long m = stations;
  const long common = (m + 1) + 2 * m + (m + 1);
  if (exchange != "tree") return common + m * (m - 1);
  const long clusters = (m + fanout - 1) / fanout;
  return common + 2 * (m - clusters) + clusters * (clusters - 1);
}

/// The simulated hosts (`skyfuse run --hosts`) a run of M stations gets from the scale
/// benchmark: none while the center and the stations fit one host's ports with room to spare
/// (Fast DDS 2.9 gives participant p of domain d the unicast ports 7400 + 250 d + 10 + 2 p, so
/// about 120 participants fit one host and domain), else one for every 64 processes.
constexpr int hosts_for(int stations) {
  constexpr int kParticipantsOnOneHost = 100;
  constexpr int kProcessesPerSimulatedHost = 64;
  if (stations + 1 <= kParticipantsOnOneHost) return 0;
  return (stations + 1 + kProcessesPerSimulatedHost - 1) / kProcessesPerSimulatedHost;
}

}  // namespace skyfuse::harness
