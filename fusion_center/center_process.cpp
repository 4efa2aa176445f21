#include "center_process.hpp"

#include "center_shards.hpp"
#include "skyfuse/registry/filter_shards.hpp"
#include "skyfuse/transport/node_setup.hpp"

namespace skyfuse::center {

int run_center(const options::NodeOptions& options) {
  const RunPlan plan = transport::load_plan(options);
  return with_filter_shard(plan.scenario.filter, [&](auto shard) {
    return run_center_in_shard<decltype(shard)::value>(options, plan);
  });
}

}  // namespace skyfuse::center
