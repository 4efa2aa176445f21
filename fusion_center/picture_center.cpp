#include "picture_center.hpp"

#include "picture_center_shards.hpp"
#include "skyfuse/registry/filter_shards.hpp"
#include "skyfuse/sim/picture_plan.hpp"
#include "skyfuse/transport/picture_nodes.hpp"

namespace skyfuse::center {

int run_picture_center(const options::NodeOptions& options, Scenario scenario) {
  PicturePlan plan = make_picture_plan(std::move(scenario), options.overrides);
  transport::refuse_unless_picture_over_dds(plan.scenario);
  return with_filter_shard(plan.scenario.filter, [&](auto shard) {
    return run_picture_center_in_shard<decltype(shard)::value>(options, std::move(plan));
  });
}

}  // namespace skyfuse::center
