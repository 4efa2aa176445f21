#include "picture_center.hpp"

#include "picture_center_shards.hpp"
#include "skyfuse/registry/filter_shards.hpp"
#include "skyfuse/sim/picture_plan.hpp"

namespace skyfuse::center {

int run_picture_center(const options::NodeOptions& options, PicturePlan plan) {
  return with_filter_shard(plan.scenario.filter, [&](auto shard) {
    return run_picture_center_in_shard<decltype(shard)::value>(options, std::move(plan));
  });
}

}  // namespace skyfuse::center
