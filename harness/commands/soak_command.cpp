#include "commands/soak_command.hpp"

#include <fmt/format.h>

#include <chrono>

#include "skyfuse/options/number_checks.hpp"
#include "skyfuse/options/scenario_option.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/sim/run_kind.hpp"
#include "skyfuse/sim/soak.hpp"

namespace skyfuse::harness {

void add_soak_command(CLI::App& app, SoakOptions& options) {
  CLI::App* cmd =
      app.add_subcommand("soak", "Long in-process run: no NaN, every covariance positive definite");
  options::add_scenario_option(*cmd, options.scenario_path);
  // The truth of every step is held (~100 bytes a step with the error traces): 5e7 steps
  // take ~5 GB.
  cmd->add_option("--steps", options.steps,
                  "Steps to run (the trajectory is flown on; ~100 bytes of memory a step)")
      ->check(options::whole_number_in(1, 50'000'000))
      ->capture_default_str();
  cmd->add_option("--stations", options.stations, "Stations M (default: all of the scenario)")
      ->check(options::whole_number_at_least(1));
}

int run_soak(const SoakOptions& options) {
  const Scenario scenario = load_scenario_or_default(options.scenario_path);
  require_one_aircraft(scenario, "soak runs");
  const int stations =
      options.stations == 0 ? static_cast<int>(scenario.stations.size()) : options.stations;
  if (stations > static_cast<int>(scenario.stations.size())) {
    throw std::invalid_argument(
        fmt::format("--stations: {} exceeds the {} stations of scenario '{}'", stations,
                    scenario.stations.size(), scenario.name));
  }
  const auto start = std::chrono::steady_clock::now();
  const SoakReport r = soak(scenario, stations, options.steps);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  fmt::print("soak: {} steps, {} stations, both architectures, {:.1f} s\n", r.steps, stations,
             seconds);
  fmt::print("  steps with a NaN/Inf or a covariance not SPD  {}\n", r.bad_steps);
  fmt::print("  smallest variance seen                        {:.3g}\n", r.min_diagonal);
  fmt::print("  p2p position RMSE, last 1000 steps            {:.3f} m\n", r.final_rmse_window_m);
  if (r.first_problem) {
    fmt::print("  first problem: {}\n", *r.first_problem);
    return 1;
  }
  return 0;
}

}  // namespace skyfuse::harness
