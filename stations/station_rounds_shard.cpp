// One shard of the station's rounds: cmake/FilterShards.cmake compiles this file once per shard,
// with SKYFUSE_SHARD set.
#include "station.hpp"

namespace skyfuse::station {

template int run_station_rounds_in_shard<SKYFUSE_SHARD>(const StationOptions& options,
                                                        const RunPlan& plan,
                                                        const StationConfig& me,
                                                        std::unique_ptr<AnyStationSensing> sensing,
                                                        transport::DdsNode& node);

}  // namespace skyfuse::station
