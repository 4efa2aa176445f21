#include "center_process.hpp"

#include "center.hpp"
#include "center_rounds.hpp"
#include "picture_center.hpp"
#include "skyfuse/registry/filter_shards.hpp"
#include "skyfuse/registry/sensor_parts.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/transport/node_setup.hpp"

namespace skyfuse::center {

int run_center(const options::NodeOptions& options) {
  if (Scenario scenario = load_scenario_or_default(options.scenario_path);
      scenario.has_many_targets()) {
    return run_picture_center(options, std::move(scenario));
  }
  const RunPlan plan = transport::load_plan(options);
  // What updates the rounds is compiled by shard of the configuration groups, the endpoints once
  // (center_rounds.hpp).
  auto rounds = with_filter_shard(plan.scenario.filter, [&](auto shard) {
    return with_sensor_part<kSensorPartsOf<decltype(shard)::value>>(
        plan.scenario, plan.stations, [&](auto part) {
          return make_center_rounds_in_shard<decltype(shard)::value, decltype(part)::value>(options,
                                                                                            plan);
        });
  });
  return transport::make_lifelong<Center>(options, plan, std::move(rounds)).run();
}

}  // namespace skyfuse::center
