#pragma once
// The station's rounds, compiled by shard of the registered filter parts
// (registry/filter_shards.hpp): defined in station.hpp, instantiated per shard by
// station_shard.cpp.

#include <cstddef>

#include "skyfuse/sim/run_plan.hpp"
#include "station_process.hpp"

namespace skyfuse::station {

/// Runs station `me` of `plan`, whose filter part lies in shard `Shard`, to the end of the run;
/// returns an options::ExitCode.
template <std::size_t Shard>
int run_station_in_shard(const StationOptions& options, const RunPlan& plan,
                         const StationConfig& me);

}  // namespace skyfuse::station
