#include "skyfuse/sim/picture_plan.hpp"

#include <fmt/format.h>

#include <memory>
#include <stdexcept>

#include "skyfuse/scenario/associator_choice.hpp"
#include "skyfuse/scenario/traffic_config.hpp"
#include "skyfuse/sim/run_kind.hpp"

namespace skyfuse {

PicturePlan make_picture_plan(Scenario scenario, const RunOverrides& overrides) {
  if (run_of(scenario) != RunOf::kManyAircraft) {
    throw std::logic_error("make_picture_plan: scenario '" + scenario.name + "' has one target");
  }
  if (overrides.speed_kmh) {
    throw std::invalid_argument(fmt::format(
        "--speed-kmh: scenario '{}' has many aircraft, each flying its own speeds", scenario.name));
  }
  PicturePlan plan;
  plan.stations = apply_stations_and_steps(scenario, overrides);
  apply_exchange_overrides(scenario, overrides.exchange, overrides.fanout);
  // The tree only when asked for: it relays the scans rather than summing them, so what it
  // saves is receptions, not a station's arithmetic (docs/picture.md, "The tree").
  if (scenario.exchange.kind == ExchangeConfig::Kind::kAuto) {
    scenario.exchange.kind = ExchangeConfig::Kind::kFlat;
  }
  if (overrides.aircraft) {
    if (!scenario.traffic->generator) {
      throw std::invalid_argument(fmt::format(
          "--aircraft: scenario '{}' generates no traffic (its aircraft are listed or recorded)",
          scenario.name));
    }
    if (*overrides.aircraft < 1) {
      throw std::invalid_argument(
          fmt::format("--aircraft: must be >= 1, got {}", *overrides.aircraft));
    }
    // The scenario is shared: the traffic config is copied before it is changed.
    auto traffic = std::make_shared<TrafficConfig>(*scenario.traffic);
    traffic->generator->aircraft = *overrides.aircraft;
    scenario.traffic = std::move(traffic);
  }
  if (overrides.associator) set_associator(scenario, *overrides.associator, "--associator");
  plan.mc_run = overrides.mc_run;
  plan.scenario = std::move(scenario);
  return plan;
}

}  // namespace skyfuse
