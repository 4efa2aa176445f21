#include "station_process.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <stdexcept>

#include "picture_station.hpp"
#include "skyfuse/registry/filter_shards.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/transport/node_setup.hpp"
#include "station_rounds.hpp"
#include "station_sensing.hpp"

namespace skyfuse::station {

int run_station(const StationOptions& options) {
  if (Scenario scenario = load_scenario_or_default(options.node.scenario_path);
      scenario.has_many_targets()) {
    return run_picture_station(options, std::move(scenario));
  }
  const RunPlan plan = transport::load_plan(options.node);
  const StationConfig* me = plan.participant(options.id);
  if (me == nullptr) {
    throw std::invalid_argument(fmt::format(
        "--id: station {} is not one of the {} participating stations of scenario '{}' (ids {})",
        options.id, plan.stations, plan.scenario.name, fmt::join(plan.participant_ids(), ", ")));
  }
  if (options.rejoin_step) {
    if (*options.rejoin_step >= static_cast<std::uint64_t>(plan.scenario.steps)) {
      throw std::invalid_argument(fmt::format("--rejoin-at-step: {} is past the run's last step {}",
                                              *options.rejoin_step, plan.scenario.steps - 1));
    }
    if (options.node.realtime_deadline_ms > 0.0) {
      throw std::invalid_argument("--rejoin-at-step: lock-step runs only, not real time");
    }
  }
  // The sensor's arithmetic is compiled by shard of the configuration groups, the rounds once per
  // fusion (station_sensing.hpp).
  auto sensing = with_filter_shard(plan.scenario.filter, [&](auto shard) {
    return make_sensing_in_shard<decltype(shard)::value>(options, plan, *me);
  });
  return with_filter_shard(plan.scenario.filter, [&](auto shard) {
    return run_station_rounds_in_shard<decltype(shard)::value>(options, plan, *me,
                                                               std::move(sensing));
  });
}

}  // namespace skyfuse::station
