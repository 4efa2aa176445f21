#pragma once
// Where a run's processes run and how they find each other: on this host's interface or each on
// a simulated host of its own (`--hosts`), discovering by multicast, through the harness's
// discovery server, or by announcing themselves to their exchange partners only
// (`--discovery`, run/discovery_peers.hpp).

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "run/run_options.hpp"
#include "run/simulated_hosts.hpp"
#include "skyfuse/options/network_options.hpp"
#include "skyfuse/scenario/scenario.hpp"

namespace skyfuse::harness {

class Placement {
 public:
  /// Throws std::invalid_argument, with the reason, for options that do not go together
  /// (before anything is created), as the constructor would.
  static void check(const RunOptions& o, std::size_t stations);
  /// Stations a process for a run of `stations` stations without --stations-per-process: one
  /// each up to kStationsAlone; above, ceil(sqrt(M)), so that processes and stations a process
  /// grow alike (16 stations: 4 of 4, 64: 8 of 8, the best measured on 2 cores:
  /// docs/performance.md#several-stations-in-one-process); but one each where a process of
  /// several is refused (--secure, --external, --kill, --restart).
  static int auto_stations_per_process(const RunOptions& o, std::size_t stations);
  static constexpr std::size_t kStationsAlone = 8;

  /// Creates the hosts if `o.hosts` asks for them. `exchange` and `stations` decide the peer
  /// lists of `--discovery peers`.
  Placement(const RunOptions& o, const ExchangeConfig& exchange, std::size_t stations);

  /// The harness's interface and discovery.
  const options::NetworkOptions& harness() const { return harness_; }
  /// The network options and namespace (-1: the harness's own) of process `i`: 0 the center,
  /// then the stations in ascending id, `--stations-per-process` to a process
  /// (run/station_groups.hpp). Round robin over the hosts, the center on the first.
  std::pair<options::NetworkOptions, int> of(std::size_t i) const;
  /// "multicast", "server ADDRESS:PORT" or "peers", for the run's summary.
  std::string discovery() const;

 private:
  // The host of process `i` (round robin: i mod hosts), with hosts only.
  int host_of(std::size_t i) const;
  // The participant id and discovery endpoint of process `i`.
  int participant_id(std::size_t i) const;
  options::Ipv4Endpoint discovery_endpoint(std::size_t i) const;
  std::string address(std::size_t i) const;

  int domain_;
  std::optional<SimulatedHosts> hosts_;
  options::NetworkOptions harness_;
  std::vector<std::vector<std::size_t>> peer_lists_;  // empty unless --discovery peers
};

}  // namespace skyfuse::harness
