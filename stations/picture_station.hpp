#pragma once
// One ground station of a run with many aircraft, as a process (docs/picture.md):
//   tick k -> predict every track of the common picture -> scan k (misses, clutter)
//          -> assign the scan's detections to the predicted tracks -> publish PictureScan
//          -> collect every station's PictureScan of step k (its own from the wire too)
//          -> rebuild each station's report against the same predicted picture and fuse
//             every track's contributions in ascending station id; manage and initiate
//          -> publish PictureRound (every track and the picture's digest).
// Every station holds the same picture bit for bit: the same inputs, the same arithmetic.

#include <vector>

#include "skyfuse/sim/picture_plan.hpp"
#include "station_process.hpp"

namespace skyfuse::station {

/// Runs station `options.id` of `plan` to the end of the run; returns an options::ExitCode.
int run_picture_station(const StationOptions& options, const PicturePlan& plan);

/// Runs stations `ids` of `plan` in this process, each on a thread of its own and all on one
/// participant (`skyfuse run --stations-per-process`); returns the first failure's
/// options::ExitCode, or success.
int run_picture_stations(const StationOptions& options, const std::vector<int>& ids,
                         const PicturePlan& plan);

}  // namespace skyfuse::station
