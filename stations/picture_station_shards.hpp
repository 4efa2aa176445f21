#pragma once
// The picture's station process by shard of the configuration groups
// (registry/filter_shards.hpp): each shard in its own translation unit
// (picture_station_shard.cpp, picture_station_node.hpp).

#include <cstddef>
#include <vector>

#include "skyfuse/sim/picture_plan.hpp"
#include "skyfuse/traffic/target_truth.hpp"
#include "station_process.hpp"

namespace skyfuse::station {

/// Runs the station of `plan` whose filter part and motion model lie in shard `Shard`; returns
/// an options::ExitCode.
template <std::size_t Shard>
int run_picture_station_in_shard(const StationOptions& options, PicturePlan plan,
                                 std::vector<TargetTruth> truth);

}  // namespace skyfuse::station
