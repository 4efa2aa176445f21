#pragma once
// One ground station of the peer-to-peer network, as a process:
//   tick k -> measurement z_k -> publish Measurement (for the center)
//          -> increment against the common prior -> publish InformationIncrement (with the prior)
//          -> collect the increments of step k until all are in or the round's deadline
//          -> fuse in ascending id onto the lowest-id contribution's prior
//          -> publish TrackEstimate -> predict to k+1.
// A restarted station (--rejoin-at-step) has no prior: in its first round it publishes only its
// measurement, takes its peers' prior from their increments, and contributes from the next.
// The estimation is the core's, chosen by the run's filter kind: SingleModelFusion
// (PeerTracker, single_model_fusion.hpp) or ImmFusion (PeerImm, imm_fusion.hpp), which sends
// one increment per mode; this file only moves samples.
//
// For simulation on one host, one process may run several stations (run_stations): each on a
// thread of its own with its own endpoints, contributions and checks, sharing the process's DDS
// participant. The wire and the results are those of one process per station; what is saved is
// the cost of a participant per station (its discovery, threads and sockets) and of the
// datagrams between stations of one process, which Fast DDS hands over in memory.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "sensor_source.hpp"
#include "skyfuse/options/node_options.hpp"

namespace skyfuse::station {

struct StationOptions {
  options::NodeOptions node;
  int id = 0;
  std::string replay_path;  ///< empty: simulate
  /// Set when the process replaces a station that died: the step it rejoins at.
  std::optional<std::uint64_t> rejoin_step;
};

/// Runs station `options.id` to the end of the run, on a participant of its own; returns an
/// options::ExitCode.
int run_station(const StationOptions& options);

/// Runs the stations `ids` of one run (of one aircraft or many) in this process, sharing one
/// participant; `options.id` is ignored. Returns kExitOk if every station ended well, else the
/// first failure's code in the order of `ids`. Throws std::invalid_argument for what several
/// stations in one process cannot do (a restart, DDS-Security's identity per station) and for
/// repeated ids.
int run_stations(const StationOptions& options, const std::vector<int>& ids);

/// Runs station(i) for every i < count, each on a thread of its own, an exception becoming its
/// exit code (options::run_node); returns kExitOk if every one returned it, else the first
/// failure's code in the order of i.
int run_on_threads(std::size_t count, const std::function<int(std::size_t)>& station);

}  // namespace skyfuse::station
