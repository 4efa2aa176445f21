// One shard of the center's rounds: cmake/FilterShards.cmake compiles this file once per shard
// and sensor part, with SKYFUSE_SHARD and SKYFUSE_SENSOR_PART set.
#include "typed_center_rounds.hpp"

namespace skyfuse::center {

template std::unique_ptr<CenterRounds>
make_center_rounds_in_shard<SKYFUSE_SHARD, SKYFUSE_SENSOR_PART>(const options::NodeOptions& options,
                                                                const RunPlan& plan);

}  // namespace skyfuse::center
