#include "skyfuse/sim/run_plan.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/sim/run_kind.hpp"

namespace skyfuse {

Vector<kKinematicsDim> RunPlan::true_initial_state() const {
  // Only the first true state is needed: a trajectory of one step, not of the whole run.
  return generate_truth(scenario.target, speed_mps, scenario.time_step_s, 1).states.front();
}

const StationConfig* CommonPlan::participant(int station_id) const {
  for (const StationConfig& s : participants()) {
    if (s.id == station_id) return &s;
  }
  return nullptr;
}

std::vector<int> CommonPlan::participant_ids() const {
  std::vector<int> ids;
  for (const StationConfig& s : participants()) ids.push_back(s.id);
  return ids;
}

std::vector<double> RunPlan::weights_of(std::span<const int> ids) const {
  std::vector<double> weights;
  for (int id : ids) weights.push_back(participant(id)->weight);
  return weights;
}

int apply_stations_and_steps(Scenario& scenario, const RunOverrides& overrides) {
  const int available = static_cast<int>(scenario.stations.size());
  const int stations = overrides.stations.value_or(available);
  if (stations < 1 || stations > available) {
    throw std::invalid_argument(
        fmt::format("--stations: must be in [1, {}] for scenario '{}', got {}", available,
                    scenario.name, stations));
  }
  if (overrides.steps) {
    if (*overrides.steps < 1) {
      throw std::invalid_argument(fmt::format("--steps: must be >= 1, got {}", *overrides.steps));
    }
    scenario.steps = *overrides.steps;
  }
  return stations;
}

RunPlan make_run_plan(Scenario scenario, const RunOverrides& overrides) {
  require_one_aircraft(scenario, "station and center processes");
  if (overrides.aircraft) {
    throw std::invalid_argument(fmt::format(
        "--aircraft: scenario '{}' has one target; the option is for one with generated traffic",
        scenario.name));
  }
  if (overrides.associator) refuse_associator_for_one_aircraft(scenario, "--associator");
  RunPlan plan;
  plan.stations = apply_stations_and_steps(scenario, overrides);
  if (overrides.speed_kmh) {
    if (!(*overrides.speed_kmh > 0.0)) {
      throw std::invalid_argument(
          fmt::format("--speed-kmh: must be > 0, got {}", *overrides.speed_kmh));
    }
    plan.speed_mps = *overrides.speed_kmh / 3.6;
    scenario.target.speeds_mps = {plan.speed_mps};
  } else {
    plan.speed_mps = scenario.target.speeds_mps.front();
    scenario.target.speeds_mps = {plan.speed_mps};
  }
  apply_exchange_overrides(scenario, overrides.exchange, overrides.fanout);
  scenario.exchange.chosen_by_size = scenario.exchange.kind == ExchangeConfig::Kind::kAuto;
  scenario.exchange.kind = chosen_exchange(scenario, static_cast<std::size_t>(plan.stations));
  validate_scenario(scenario, "run options");
  plan.mc_run = overrides.mc_run;
  plan.scenario = std::move(scenario);
  return plan;
}

}  // namespace skyfuse
