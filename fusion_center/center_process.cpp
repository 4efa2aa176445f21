#include "center_process.hpp"

#include "center.hpp"
#include "center_rounds.hpp"
#include "picture_center.hpp"
#include "skyfuse/registry/filter_shards.hpp"
#include "skyfuse/registry/sensor_parts.hpp"
#include "skyfuse/transport/node_plan.hpp"

namespace skyfuse::center {

int run_center(const options::NodeOptions& options) {
  // The run's kind is its plan's (sim/any_plan.hpp), which every node builds alike.
  AnyPlan any_plan = transport::load_any_plan(options);
  if (auto* picture = std::get_if<PicturePlan>(&any_plan)) {
    return run_picture_center(options, std::move(*picture));
  }
  const RunPlan& plan = std::get<RunPlan>(any_plan);
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
