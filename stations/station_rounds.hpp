#pragma once
// The station's rounds over DDS, once its sensing is made: defined in station.hpp, compiled once
// per fusion (station_fusions.hpp), in the shard of the first configuration group whose fusion
// it is (station_rounds_shard.cpp).

#include <cstddef>
#include <memory>

#include "skyfuse/sim/run_plan.hpp"
#include "station_process.hpp"
#include "station_sensing.hpp"

namespace skyfuse::transport {
class DdsNode;
}

namespace skyfuse::station {

/// Runs station `me` of `plan`, whose filter part on its motion model fuses by `Fusion`
/// (station_fusions.hpp), to the end of the run, its measurements and contributions made by
/// `sensing` (made for the run's filter part and model by make_sensing_in_shard); returns an
/// options::ExitCode.
template <typename Fusion>
int run_station_rounds(const StationOptions& options, const RunPlan& plan, const StationConfig& me,
                       std::unique_ptr<AnyStationSensing> sensing, transport::DdsNode& node);

}  // namespace skyfuse::station
