// One shard of the picture's center process: cmake/FilterShards.cmake compiles this file once
// per shard and sensor part, with SKYFUSE_SHARD and SKYFUSE_SENSOR_PART set.
#include "picture_center_node.hpp"

namespace skyfuse::center {

template int run_picture_center_in_shard<SKYFUSE_SHARD, SKYFUSE_SENSOR_PART>(
    const options::NodeOptions& options, PicturePlan plan);

}  // namespace skyfuse::center
