#pragma once
// The fusion center as a process: collect every station's raw measurement of step k, run the
// stacked-measurement filter of the run's filter kind (central_fusion.hpp: the stacked EKF, or
// the IMM with every mode on the stacked measurement), publish the track, predict.

#include "skyfuse/options/node_options.hpp"

namespace skyfuse::center {

/// Runs the center to the end of the run; returns a options::ExitCode.
int run_center(const options::NodeOptions& options);

/// The source id of the center's tracks (stations have ids >= 1).
inline constexpr int kCenterSourceId = 0;

}  // namespace skyfuse::center
