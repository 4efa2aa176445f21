#pragma once
// The picture's station process by shard of the configuration groups
// (registry/filter_shards.hpp): each shard in its own translation unit
// (picture_station_shard.cpp, picture_station_node.hpp).

#include <cstddef>
#include <vector>

#include "skyfuse/sim/picture_plan.hpp"
#include "skyfuse/traffic/target_truth.hpp"
#include "station_process.hpp"

namespace skyfuse::transport {
class DdsNode;
}  // namespace skyfuse::transport

namespace skyfuse::station {

/// Runs the station of `plan` whose filter part and motion model lie in shard `Shard` on
/// participant `node` (its own, or its process's); returns an options::ExitCode.
template <std::size_t Shard>
int run_picture_station_in_shard(const StationOptions& options, PicturePlan plan,
                                 const std::vector<TargetTruth>& truth, transport::DdsNode& node);

}  // namespace skyfuse::station
