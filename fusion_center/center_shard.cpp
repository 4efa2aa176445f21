// One shard of the center's rounds: cmake/FilterShards.cmake compiles this file once per shard,
// with SKYFUSE_SHARD set.
#include "center.hpp"

namespace skyfuse::center {

template int run_center_in_shard<SKYFUSE_SHARD>(const options::NodeOptions& options,
                                                const RunPlan& plan);

}  // namespace skyfuse::center
