#pragma once
// The picture's center process by shard of the configuration groups
// (registry/filter_shards.hpp): each shard in its own translation unit
// (picture_center_shard.cpp, picture_center_node.hpp).

#include <cstddef>

#include "skyfuse/options/node_options.hpp"
#include "skyfuse/sim/picture_plan.hpp"

namespace skyfuse::center {

/// Runs the center of `plan`, whose filter part and motion model lie in shard `Shard`; returns
/// an options::ExitCode.
template <std::size_t Shard>
int run_picture_center_in_shard(const options::NodeOptions& options, PicturePlan plan);

}  // namespace skyfuse::center
