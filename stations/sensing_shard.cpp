// One shard of the stations' sensing: cmake/FilterShards.cmake compiles this file once per
// shard, with SKYFUSE_SHARD set.
#include "sensing_parts.hpp"

namespace skyfuse::station {

template std::unique_ptr<AnyStationSensing> make_sensing_in_shard<SKYFUSE_SHARD>(
    const StationOptions& options, const RunPlan& plan, const StationConfig& me);

}  // namespace skyfuse::station
