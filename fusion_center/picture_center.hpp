#pragma once
// The fusion center of a run with many aircraft, as a process: each round it takes every
// station's PictureScan as the raw scan it is (the detections; the station's own decisions are
// the peers' business), assigns all of them jointly to its predicted picture and updates it
// (picture/central_picture.hpp), and publishes its picture (PictureRound, source 0). The
// same inputs as the peers': the architectures are compared on identical data.

#include "skyfuse/options/node_options.hpp"
#include "skyfuse/sim/picture_plan.hpp"

namespace skyfuse::center {

/// Runs the center of `plan`; returns an options::ExitCode.
int run_picture_center(const options::NodeOptions& options, PicturePlan plan);

}  // namespace skyfuse::center
