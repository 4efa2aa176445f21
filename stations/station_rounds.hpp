#pragma once
// The station's rounds over DDS, once its sensing is made: defined in station.hpp, compiled by
// shard of the configuration groups in station_rounds_shard.cpp.

#include <cstddef>
#include <memory>

#include "skyfuse/sim/run_plan.hpp"
#include "station_process.hpp"
#include "station_sensing.hpp"

namespace skyfuse::transport {
class DdsNode;
}

namespace skyfuse::station {

/// Runs station `me` of `plan`, whose filter part and motion model lie in shard `Shard`, to the end
/// of the run, its measurements and contributions made by `sensing` (made for the run's filter part
/// and model by make_sensing_in_shard); returns an options::ExitCode.
template <std::size_t Shard>
int run_station_rounds_in_shard(const StationOptions& options, const RunPlan& plan,
                                const StationConfig& me, std::unique_ptr<AnyStationSensing> sensing,
                                transport::DdsNode& node);

}  // namespace skyfuse::station
