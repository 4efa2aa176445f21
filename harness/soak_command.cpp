#include "soak_command.hpp"

#include <fmt/format.h>

#include <chrono>

#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/sim/soak.hpp"
#include "skyfuse/transport/scenario_option.hpp"

namespace skyfuse::harness {

void add_soak_command(CLI::App& app, SoakOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "soak", "Long in-process run: no NaN, every covariance symmetric positive definite");
  transport::add_scenario_option(*cmd, options.scenario_path);
  cmd->add_option("--steps", options.steps, "Steps to run (the trajectory is flown on)")
      ->check(CLI::Range(std::int64_t{1}, std::int64_t{2'000'000'000}))
      ->capture_default_str();
  cmd->add_option("--stations", options.stations, "Stations M (default: all of the scenario)")
      ->check(CLI::PositiveNumber);
}

int run_soak(const SoakOptions& options) {
  const Scenario scenario = load_scenario_or_default(options.scenario_path);
  const int stations =
      options.stations == 0 ? static_cast<int>(scenario.stations.size()) : options.stations;
  const auto start = std::chrono::steady_clock::now();
  const SoakReport r = soak(scenario, stations, options.steps);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  fmt::print("soak: {} steps, {} stations, both architectures, {:.1f} s\n", r.steps, stations,
             seconds);
  fmt::print("  steps with a NaN/Inf or a covariance not SPD  {}\n", r.bad_steps);
  fmt::print("  max |P - P^T| / max |P|                       {:.3g}\n", r.max_relative_asymmetry);
  fmt::print("  smallest variance seen                        {:.3g}\n", r.min_diagonal);
  fmt::print("  p2p position RMSE, last 1000 steps            {:.3f} m\n", r.final_rmse_window_m);
  if (r.first_problem) {
    fmt::print("  first problem: {}\n", *r.first_problem);
    return 1;
  }
  return 0;
}

}  // namespace skyfuse::harness
