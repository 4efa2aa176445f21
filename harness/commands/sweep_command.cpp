#include "commands/sweep_command.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <type_traits>
#include <variant>

#include "report/picture_report.hpp"
#include "report/registration_report.hpp"
#include "report/sweep_report.hpp"
#include "report/sweep_runner.hpp"
#include "skyfuse/options/node_options.hpp"
#include "skyfuse/options/number_checks.hpp"
#include "skyfuse/options/scenario_option.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/sim/monte_carlo.hpp"
#include "skyfuse/sim/picture_run.hpp"
#include "skyfuse/sim/sweep_plan.hpp"
#include "skyfuse/traffic/traffic_truth.hpp"

namespace skyfuse::harness {

void add_sweep_command(CLI::App& app, SweepOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "sweep", "Monte-Carlo comparison of central and peer-to-peer fusion, in-process");
  options::add_scenario_option(*cmd, options.scenario_path);
  cmd->add_option("--runs", options.runs, "Monte-Carlo runs per (M, speed)")
      ->check(options::whole_number_in(1, 1000000))
      ->capture_default_str();
  SweepOverrides& overrides = options.overrides;
  cmd->add_option("--max-stations", overrides.max_stations,
                  "Largest M; runs M = 1..M_max using the first M stations (default: all)")
      ->check(options::whole_number_in(1, 100000));
  cmd->add_option("--only-stations", overrides.only_stations,
                  "Only the scenario's stations of these ids (e.g. 1,2,3): the same run seen by "
                  "some of its sensors (default: every station)")
      ->delimiter(',');
  cmd->add_option("--out", options.out_dir, "Folder for sweep.csv, sweep.json and sweep.png")
      ->capture_default_str();
  cmd->add_option("--seed", overrides.seed, "Override the scenario's seed");
  cmd->add_option("--steps", overrides.steps, "Override the scenario's number of steps")
      ->check(options::whole_number_in(1, 100000000));
  cmd->add_option("--threads", options.threads, "Worker threads (default: one per core)")
      ->check(options::whole_number_in(0, 1024));
  options::add_exchange_options(*cmd, overrides.exchange, overrides.fanout);
  options::add_associator_option(*cmd, overrides.associator);
  cmd->add_flag("!--no-plot", options.plot, "Skip the PNG plot");
  cmd->add_option("--traffic-file", overrides.traffic_file,
                  "An OpenSky state-vector CSV to fly instead of the scenario's recorded file "
                  "(a scenario with 'traffic: recorded')")
      ->check(CLI::ExistingFile);
}

namespace {

// Many aircraft: their picture, run in-process --runs times, on --threads workers.
int run_picture_sweep(const PictureSweep& sweep, const SweepOptions& options,
                      const std::filesystem::path& out_dir) {
  const Scenario& scenario = sweep.scenario;
  const TrafficTruth truth = build_traffic_truth(scenario, sweep.traffic_file);
  PictureReport report{scenario, truth, {}};
  report.runs =
      run_picture_runs(scenario, truth.targets, options.runs, sweep.stations, options.threads);
  print_picture_table(report, stdout);
  print_registration_table(report, stdout);
  write_picture_csv(report, out_dir / "picture.csv");
  write_picture_json(report, out_dir / "picture.json");
  fmt::print("wrote {}/picture.csv and picture.json\n", out_dir.string());
  if (!report.runs.empty() && !report.runs.front().registration.empty()) {
    write_registration_csv(report, out_dir / "registration.csv");
    fmt::print("wrote {}/registration.csv\n", out_dir.string());
  }
  // A broken guarantee is a failed run, whatever the figures.
  return picture_guarantees_held(report) ? 0 : 1;
}

// One aircraft: central and peer-to-peer for every speed and M = 1..max, --runs times each.
int run_one_aircraft_sweep(const OneAircraftSweep& sweep, const SweepOptions& options,
                           const std::filesystem::path& out_dir) {
  const std::vector<MonteCarloSummary> rows =
      run_sweep_rows(sweep.scenario, options.runs, sweep.max_stations, options.threads);
  const SweepReport report{sweep.scenario, rows};
  print_sweep_table(report, stdout);
  write_sweep_csv(report, out_dir / "sweep.csv");
  write_sweep_json(report, out_dir / "sweep.json");
  fmt::print("wrote {}/sweep.csv and sweep.json\n", out_dir.string());
  if (options.plot) {
    const std::filesystem::path png = out_dir / "sweep.png";
    if (plot_sweep(out_dir / "sweep.csv", png)) {
      fmt::print("wrote {}\n", png.string());
    } else {
      fmt::print(stderr, "skyfuse: warning: plot not written (needs python3-matplotlib)\n");
    }
  }
  return 0;
}

}  // namespace

int run_sweep(const SweepOptions& options) {
  // The sweep's kind is its plan's (sim/sweep_plan.hpp).
  const SweepPlan plan =
      make_sweep_plan(load_scenario_or_default(options.scenario_path), options.overrides);
  const std::filesystem::path out_dir(options.out_dir);
  std::filesystem::create_directories(out_dir);
  return std::visit(
      [&](const auto& sweep) {
        if constexpr (std::is_same_v<std::decay_t<decltype(sweep)>, PictureSweep>) {
          return run_picture_sweep(sweep, options, out_dir);
        } else {
          return run_one_aircraft_sweep(sweep, options, out_dir);
        }
      },
      plan);
}

}  // namespace skyfuse::harness
