#include "commands/demo_command.hpp"

#include <fmt/format.h>

#include <cmath>
#include <ctime>
#include <string>
#include <thread>
#include <vector>

#include "report/output_files.hpp"
#include "run/execute_run.hpp"
#include "run/kernel_counters.hpp"
#include "skyfuse/options/number_checks.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/sim/monte_carlo.hpp"
#include "skyfuse/transport/node_config.hpp"

namespace skyfuse::harness {

void add_demo_command(CLI::App& app, DemoOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "demo",
      "The default scenario through the real system: 4 station processes + the center "
      "over DDS at each speed, compared with the in-process result");
  cmd->add_option("--out", o.out_dir, "Results folder (default: results/demo-<date>-<time>)");
  cmd->add_option("--domain", o.domain, "DDS domain id")
      ->check(options::whole_number_in(0, transport::kMaxDomainId))
      ->capture_default_str();
  cmd->add_option("--stations", o.stations, "Number of station processes")
      ->check(options::whole_number_at_least(1))
      ->capture_default_str();
}

int run_demo(const DemoOptions& d) {
  std::string out_dir = d.out_dir;
  if (out_dir.empty()) {
    const std::time_t now = std::time(nullptr);
    char stamp[32];
    std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", std::localtime(&now));
    out_dir = fmt::format("results/demo-{}", stamp);
  }
  const Scenario scenario = load_default_scenario();
  struct Row {
    RunSummary dds;
    double rmse_in_process_central;
    double rmse_in_process_p2p;
  };
  std::vector<Row> rows;
  std::vector<std::string> step_files;
  for (double speed : scenario.target.speeds_mps) {
    RunOptions o;
    o.node.domain = d.domain;
    o.node.overrides.stations = d.stations;
    o.node.overrides.speed_kmh = speed * 3.6;
    o.out_dir = fmt::format("{}/{:.0f}kmh", out_dir, speed * 3.6);
    o.record_path = o.out_dir + "/run.mcap";
    const RunPlan plan = make_run_plan(scenario, o.node.overrides);
    const RunSummary dds = execute_run(o, plan);

    // The same run in-process: same core code, same seed, same Monte-Carlo index.
    const RunTrace trace = simulate_run(plan.scenario, plan.truth(), plan.stations, plan.mc_run);
    double sc = 0.0;
    double sp = 0.0;
    for (std::size_t k = 0; k < trace.sq_error_central.size(); ++k) {
      sc += trace.sq_error_central[k];
      sp += trace.sq_error_p2p[k];
    }
    const auto n = static_cast<double>(trace.sq_error_central.size());
    rows.push_back({dds, std::sqrt(sc / n), std::sqrt(sp / n)});
    step_files.push_back(o.out_dir + "/steps.csv");
  }

  // Rounds/s and latency are this host's: the machine is named with them.
  fmt::print(
      "\nskyfuse demo: paper000, {} station processes + fusion center over DDS (loopback) on {}, "
      "{} cores\n",
      d.stations, cpu_model(), std::thread::hardware_concurrency());
  fmt::print("{:>6} {:>13} {:>13} {:>15} {:>15} {:>13} {:>9} {:>17}\n", "km/h", "RMSE central",
             "RMSE p2p", "in-process c/p", "max|c-p2p| m", "max|peer-peer|", "rounds/s",
             "latency p50/p99 us");
  for (const Row& r : rows) {
    fmt::print(
        "{:>6.0f} {:>12.4f}m {:>12.4f}m {:>7.4f}/{:.4f} {:>15.2e} {:>14.1e} {:>9.0f} "
        "{:>8.0f}/{:.0f}\n",
        r.dds.speed_kmh, r.dds.rmse_central_m, r.dds.rmse_p2p_m, r.rmse_in_process_central,
        r.rmse_in_process_p2p, r.dds.max_abs_diff_central_vs_p2p, r.dds.max_abs_diff_between_peers,
        r.dds.rounds_per_s, r.dds.round_latency_us_p50, r.dds.round_latency_us_p99);
  }
  std::vector<std::string> plot_args{out_dir + "/demo.png"};
  plot_args.insert(plot_args.end(), step_files.begin(), step_files.end());
  if (!run_plot_script("plot_run.py", plot_args)) {
    fmt::print(stderr, "skyfuse: warning: plot not written (needs python3-matplotlib)\n");
  }
  fmt::print(
      "\nresults in {0}/ (per speed: steps.csv, tracks.csv, measurements.csv, summary.json, "
      "run.mcap; demo.png)\nsee a recording: skyfuse view {0}/{1:.0f}kmh/run.mcap, or open it "
      "in Foxglove or Lichtblick\n",
      out_dir, scenario.target.speeds_mps.front() * 3.6);
  return 0;
}

}  // namespace skyfuse::harness
