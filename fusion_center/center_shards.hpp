#pragma once
// The center's rounds, compiled by shard of the registered filter parts
// (registry/filter_shards.hpp): defined in center.hpp, instantiated per shard by
// center_shard.cpp.

#include <cstddef>

#include "skyfuse/options/node_options.hpp"
#include "skyfuse/sim/run_plan.hpp"

namespace skyfuse::center {

/// Runs the center of `plan`, whose filter part lies in shard `Shard`, to the end of the run;
/// returns an options::ExitCode.
template <std::size_t Shard>
int run_center_in_shard(const options::NodeOptions& options, const RunPlan& plan);

}  // namespace skyfuse::center
