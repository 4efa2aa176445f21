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

#include <cstdint>
#include <memory>
#include <optional>

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

/// Runs the station to the end of the run; returns a options::ExitCode.
int run_station(const StationOptions& options);

}  // namespace skyfuse::station
