#pragma once
// The fusion center as a process: collect every station's raw measurement of step k, run the
// stacked-measurement EKF (the core's CentralTracker), publish the track, predict.

#include "skyfuse/options/node_options.hpp"

namespace skyfuse::center {

/// Runs the center to the end of the run; returns a options::ExitCode.
int run_center(const options::NodeOptions& options);

/// The source id of the center's tracks (stations have ids >= 1).
inline constexpr int kCenterSourceId = 0;

}  // namespace skyfuse::center
