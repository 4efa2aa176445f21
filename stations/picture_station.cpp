#include "picture_station.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <stdexcept>
#include <vector>

#include "picture_station_shards.hpp"
#include "skyfuse/registry/filter_shards.hpp"
#include "skyfuse/sim/picture_plan.hpp"
#include "skyfuse/traffic/traffic_truth.hpp"

namespace skyfuse::station {

int run_picture_station(const StationOptions& options, Scenario scenario) {
  PicturePlan plan = make_picture_plan(std::move(scenario), options.node.overrides);
  bool participates = false;
  std::vector<int> ids;
  for (const StationConfig& s : plan.participants()) {
    ids.push_back(s.id);
    participates = participates || s.id == options.id;
  }
  if (!participates) {
    throw std::invalid_argument(fmt::format(
        "--id: station {} is not one of the {} participating stations of scenario '{}' (ids {})",
        options.id, plan.stations, plan.scenario.name, fmt::join(ids, ", ")));
  }
  if (!options.replay_path.empty()) {
    throw std::invalid_argument("--replay: not for a run of many aircraft yet");
  }
  if (options.rejoin_step &&
      *options.rejoin_step >= static_cast<std::uint64_t>(plan.scenario.steps)) {
    throw std::invalid_argument(fmt::format("--rejoin-at-step: {} is past the run's last step {}",
                                            *options.rejoin_step, plan.scenario.steps - 1));
  }
  std::vector<TargetTruth> truth =
      build_traffic_truth(plan.scenario, options.node.traffic_file).targets;
  return with_filter_shard(plan.scenario.filter, [&](auto shard) {
    return run_picture_station_in_shard<decltype(shard)::value>(options, std::move(plan),
                                                                std::move(truth));
  });
}

}  // namespace skyfuse::station
