// One shard of the picture's station process: cmake/FilterShards.cmake compiles this file once
// per shard, with SKYFUSE_SHARD set.
#include "picture_station_node.hpp"

namespace skyfuse::station {

template int run_picture_station_in_shard<SKYFUSE_SHARD>(const StationOptions& options,
                                                         PicturePlan plan,
                                                         const std::vector<TargetTruth>& truth,
                                                         transport::DdsNode& node);

}  // namespace skyfuse::station
