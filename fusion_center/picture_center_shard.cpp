// One shard of the picture's center process: cmake/FilterShards.cmake compiles this file once
// per shard, with SKYFUSE_SHARD set.
#include "picture_center_node.hpp"

namespace skyfuse::center {

template int run_picture_center_in_shard<SKYFUSE_SHARD>(const options::NodeOptions& options,
                                                        PicturePlan plan);

}  // namespace skyfuse::center
