#pragma once
// One ground station of the peer-to-peer network, as a process:
//   tick k -> measurement z_k -> publish Measurement (for the center)
//          -> increment against the common prior -> publish InformationIncrement
//          -> collect every station's increment of step k -> fuse in ascending id
//          -> publish TrackEstimate -> predict to k+1.
// The estimation is the core's (PeerTracker); this file only moves samples.

#include <memory>

#include "sensor_source.hpp"
#include "skyfuse/transport/node_options.hpp"

namespace skyfuse::station {

struct StationOptions {
  transport::NodeOptions node;
  int id = 0;
  std::string replay_path;  ///< empty: simulate
};

/// Runs the station to the end of the run; returns a transport::ExitCode.
int run_station(const StationOptions& options);

}  // namespace skyfuse::station
