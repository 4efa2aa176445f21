#include "skyfuse/sim/sweep_plan.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "skyfuse/scenario/associator_choice.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/sim/run_kind.hpp"

namespace skyfuse {
namespace {

// Keeps the stations of `scenario` whose ids `ids` lists, in the scenario's order.
void keep_only_stations(Scenario& scenario, const std::vector<int>& ids) {
  for (const int id : ids) {
    if (std::none_of(scenario.stations.begin(), scenario.stations.end(),
                     [&](const StationConfig& s) { return s.id == id; })) {
      throw std::invalid_argument(
          fmt::format("--only-stations: scenario '{}' has no station {}", scenario.name, id));
    }
  }
  std::erase_if(scenario.stations, [&](const StationConfig& s) {
    return std::find(ids.begin(), ids.end(), s.id) == ids.end();
  });
  validate_scenario(scenario, "--only-stations");
}

}  // namespace

SweepPlan make_sweep_plan(Scenario scenario, const SweepOverrides& overrides) {
  if (overrides.seed) scenario.seed = *overrides.seed;
  apply_exchange_overrides(scenario, overrides.exchange, overrides.fanout);
  if (overrides.steps) {
    scenario.steps = *overrides.steps;
    validate_scenario(scenario, "--steps");
  }
  if (!overrides.only_stations.empty()) keep_only_stations(scenario, overrides.only_stations);
  const int available = static_cast<int>(scenario.stations.size());
  const int stations = overrides.max_stations.value_or(available);
  if (stations > available) {
    throw std::invalid_argument(
        fmt::format("--max-stations: {} exceeds the {} stations of scenario '{}'", stations,
                    available, scenario.name));
  }
  if (run_of(scenario) == RunOf::kManyAircraft) {
    if (overrides.associator) set_associator(scenario, *overrides.associator, "--associator");
    return PictureSweep{std::move(scenario), stations, overrides.traffic_file};
  }
  if (overrides.associator) refuse_associator_for_one_aircraft(scenario, "--associator");
  if (!overrides.traffic_file.empty()) {
    throw std::invalid_argument(fmt::format(
        "--traffic-file: scenario '{}' has one target; the option is for one with 'traffic'",
        scenario.name));
  }
  return OneAircraftSweep{std::move(scenario), stations};
}

}  // namespace skyfuse
