#include "commands/bench_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <thread>

#include "floors/echo_floor.hpp"
#include "report/output_files.hpp"
#include "run/bench_scenario.hpp"
#include "run/execute_run.hpp"
#include "run/kernel_counters.hpp"
#include "run/lockstep_driver.hpp"
#include "skyfuse/options/number_checks.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/transport/qos.hpp"
#include "skyfuse/transport/shutdown.hpp"

namespace skyfuse::harness {
namespace {

// Runs the Google Benchmark binary beside this one and returns median real times in ns by
// benchmark name ("StationStep", "FuseIncrements/4", ...).
std::map<std::string, double> micro_benchmark_medians(const std::filesystem::path& out) {
  const auto json_path = out / "micro.json";
  const std::string command = fmt::format(
      "'{}' --benchmark_repetitions=5 --benchmark_report_aggregates_only=true "
      "--benchmark_out='{}' --benchmark_out_format=json > /dev/null 2>&1",
      helper_program("skyfuse_core_bench").string(), json_path.string());
  if (std::system(command.c_str()) != 0) {
    throw std::runtime_error("micro-benchmarks failed: " + command);
  }
  std::ifstream in(json_path);
  const auto doc = nlohmann::json::parse(in);
  std::map<std::string, double> medians;
  for (const auto& b : doc.at("benchmarks")) {
    if (b.value("aggregate_name", "") != "median") continue;
    double ns = b.at("real_time").get<double>();
    const std::string unit = b.value("time_unit", "ns");
    if (unit == "us") ns *= 1e3;
    if (unit == "ms") ns *= 1e6;
    medians[b.at("run_name").get<std::string>()] = ns;
  }
  return medians;
}

// Runs the micro-benchmarks, prints their table and returns bench.json's "micro_ns".
nlohmann::json micro_benchmark_section(const std::filesystem::path& out) {
  fmt::print("\nmicro-benchmarks (median of 5, ns)...\n");
  const auto m = micro_benchmark_medians(out);
  nlohmann::json fuse;
  nlohmann::json stacked;
  fmt::print("{:>5} {:>14} {:>14} {:>10}\n", "M", "fuse M incr.", "stacked EKF", "ratio");
  for (int k = 1; k <= 128; k *= 2) {
    const std::string key = std::to_string(k);
    const double f = m.at("FuseIncrements/" + key);
    const double s = m.at("StackedEkfUpdate/" + key);
    fuse[key] = f;
    stacked[key] = s;
    fmt::print("{:>5} {:>14.0f} {:>14.0f} {:>9.1f}x\n", k, f, s, s / f);
  }
  fmt::print("station step (predict + measurement model + increment): {:.0f} ns\n",
             m.at("StationStep"));
  return {{"station_step", m.at("StationStep")},
          {"predict", m.at("Predict")},
          {"fuse_increments", fuse},
          {"stacked_ekf_update", stacked}};
}

// Prints one station count's line of the DDS table and returns its row of bench.json.
nlohmann::json report_row(int m, int rounds, const RunSummary& s, const FloorResult& floor,
                          const FloorResult& all_to_all) {
  const double ratio = s.rounds_per_s / floor.rounds_per_s;
  const double ratio_all_to_all = s.rounds_per_s / all_to_all.rounds_per_s;
  fmt::print("{:>4} {:>9.0f} {:>9.0f} {:>5.0f}% {:>12.0f} {:>5.0f}% {:>23} {:>17} {:>8.2f} s\n", m,
             s.rounds_per_s, floor.rounds_per_s, 100.0 * ratio, all_to_all.rounds_per_s,
             100.0 * ratio_all_to_all,
             fmt::format("{:.0f}/{:.0f}/{:.0f}", s.round_latency_us_p50, s.round_latency_us_p99,
                         s.round_latency_us_max),
             fmt::format("{:.0f}/{:.0f}", floor.latency_us_p50, floor.latency_us_p99),
             s.discovery_s);
  return {{"stations", m},
          {"rounds", rounds},
          {"rounds_per_s", s.rounds_per_s},
          {"floor_rounds_per_s", floor.rounds_per_s},
          {"ratio_to_floor", ratio},
          {"all_to_all_floor_rounds_per_s", all_to_all.rounds_per_s},
          {"ratio_to_all_to_all_floor", ratio_all_to_all},
          {"all_to_all_floor_latency_us_p50", all_to_all.latency_us_p50},
          {"all_to_all_floor_latency_us_p99", all_to_all.latency_us_p99},
          {"round_latency_us_p50", s.round_latency_us_p50},
          {"round_latency_us_p99", s.round_latency_us_p99},
          {"round_latency_us_max", s.round_latency_us_max},
          {"floor_latency_us_p50", floor.latency_us_p50},
          {"floor_latency_us_p99", floor.latency_us_p99},
          {"discovery_s", s.discovery_s},
          {"floor_discovery_s", floor.discovery_s}};
}

RunSummary run_for_bench(const BenchOptions& o, const Scenario& scenario,
                         const std::string& scenario_path, int m,
                         const std::filesystem::path& out) {
  RunOptions run;
  run.node.scenario_path = scenario_path;
  run.node.overrides.stations = m;
  run.node.overrides.steps = o.rounds;
  run.node.domain = o.domain;
  run.out_dir = (out / fmt::format("run-M{}", m)).string();
  run.round_timeout_s = 30.0;
  return execute_run(run, make_run_plan(scenario, run.node.overrides));
}

// The floor runs on a domain of its own: whatever the floor's processes leave behind on
// leaving (late announcements, a killed echo's lease), the run's discovery never sees it.
int floor_domain(int domain) {
  return domain < transport::kMaxDomainId ? domain + 1 : domain - 1;
}

}  // namespace

void add_bench_command(CLI::App& app, BenchOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "bench", "Micro-benchmarks and the DDS round rate against the bare Fast DDS floor");
  cmd->add_option("--out", o.out_dir, "Folder for bench.json")->capture_default_str();
  cmd->add_option("--scenario", o.scenario_path,
                  "Scenario with enough stations (default: scenarios/ring64.yaml beside skyfuse)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--stations", o.stations, "Station counts to measure")
      ->check(options::whole_number_at_least(1))
      ->capture_default_str();
  cmd->add_option("--rounds", o.rounds, "Lock-step rounds per measurement")
      ->check(options::whole_number_in(10, 1000000))
      ->capture_default_str();
  cmd->add_option("--domain", o.domain,
                  fmt::format("DDS domain id of the runs (the floors use the next id; {} when "
                              "this is {})",
                              transport::kMaxDomainId - 1, transport::kMaxDomainId))
      ->check(options::whole_number_in(0, transport::kMaxDomainId))
      ->capture_default_str();
  cmd->add_flag("!--no-micro", o.micro, "Skip the micro-benchmarks");

  CLI::Option* scale =
      cmd->add_flag("--scale", o.scale_requested,
                    "The scale benchmark instead: flat against tree exchange as M grows, lock-step "
                    "and real time (scale.json, scale.csv, scale.png in --out, default "
                    "results/scale; stations default 4 8 16 32 64, scenario ring256.yaml)");
  cmd->add_option("--exchange", o.scale.exchanges, "--scale: the exchanges to compare")
      ->check(CLI::IsMember({"flat", "tree"}))
      ->capture_default_str();
  cmd->add_option("--fanout", o.scale.fanout, "--scale: the tree's stations per cluster")
      ->check(options::whole_number_in(2, ExchangeConfig::kMaxFanout))
      ->capture_default_str();
  cmd->add_option("--realtime-steps", o.scale.realtime_steps,
                  "--scale: steps of each real-time run (0: none)")
      ->check(options::whole_number_in(0, 1000000))
      ->capture_default_str();
  cmd->add_option("--realtime-deadline-ms", o.scale.realtime_deadline_ms,
                  "--scale: the real-time runs' deadline")
      ->check(options::positive_number())
      ->capture_default_str();
  options::add_discovery_option(
      *cmd, o.scale.host_discovery,
      "--scale: how runs on simulated hosts (M above one host's limit) discover each other: "
      "each process announcing itself to its exchange partners only (peers), by multicast "
      "across the hosts' bridge, or through the harness's discovery server (server or auto)");
  cmd->add_option("--aircraft", o.scale.aircraft,
                  "--scale: numbers of aircraft, to measure a run of many aircraft instead (flat "
                  "exchange; stations default 8 16, scenario uam-metro.yaml, real-time "
                  "deadline 80 ms)")
      ->check(options::whole_number_in(1, 100000))
      ->needs(scale);
  cmd->add_option("--stations-per-process", o.scale.stations_per_process,
                  "--scale: stations in each station process, sharing its participant (skyfuse "
                  "run --stations-per-process)")
      ->check(CLI::Range(1, 256))
      ->needs(scale);
  cmd->add_flag("!--reliable", o.scale.best_effort,
                "--scale: reliable increments, sums and measurements (default: best effort)");
  // The options the two benchmarks share go to the scale benchmark only when given, so that
  // each keeps its own defaults.
  cmd->callback([cmd, &o] {
    if (!o.scale_requested) return;
    if (cmd->count("--out") > 0) o.scale.out_dir = o.out_dir;
    if (cmd->count("--scenario") > 0) o.scale.scenario_path = o.scenario_path;
    if (cmd->count("--stations") > 0) o.scale.stations = o.stations;
    if (cmd->count("--rounds") > 0) o.scale.rounds = o.rounds;
    o.scale.domain = o.domain;
    // A run of many aircraft: its own defaults, a 10 Hz scan's share of a round.
    if (!o.scale.aircraft.empty()) {
      if (cmd->count("--stations") == 0) o.scale.stations = {8, 16};
      if (cmd->count("--realtime-deadline-ms") == 0) o.scale.realtime_deadline_ms = 80.0;
    }
  });
}

int run_bench(const BenchOptions& o) {
  if (o.scale_requested) return run_scale_bench(o.scale);
  const auto [scenario_path, scenario] =
      load_bench_scenario(o.scenario_path, "ring64.yaml", o.stations);
  const std::filesystem::path out(o.out_dir);
  std::filesystem::create_directories(out);

  nlohmann::json doc;
  doc["machine"] = {{"cores", std::thread::hardware_concurrency()},
                    {"cpu_model", cpu_model()},
                    {"rmem_max", transport::receive_buffer_cap().value_or(0)}};
  fmt::print("skyfuse bench on {} ({} cores)\n", cpu_model(), std::thread::hardware_concurrency());

  if (o.micro) doc["micro_ns"] = micro_benchmark_section(out);

  const int largest =
      o.stations.empty() ? 0 : *std::max_element(o.stations.begin(), o.stations.end());
  warn_if_receive_buffers_too_small(largest);
  fmt::print(
      "\nlock-step rounds over DDS ({} rounds each; floor = commander + M echo processes; "
      "all-to-all = the same, each echo also exchanging a sample with the others)\n",
      o.rounds);
  fmt::print("{:>4} {:>9} {:>9} {:>6} {:>11} {:>6} {:>23} {:>17} {:>10}\n", "M", "rounds/s",
             "floor/s", "ratio", "all-to-all/s", "ratio", "latency p50/p99/max us",
             "floor p50/p99 us", "discovery");
  nlohmann::json rows = nlohmann::json::array();
  // Rewritten after every station count: a bench of hours keeps what it measured if stopped.
  const auto save_rows = [&] {
    doc["dds"] = rows;
    write_file_atomically(out / "bench.json", doc.dump(2) + "\n");
  };
  transport::NodeConfig floor_config;
  floor_config.domain_id = floor_domain(o.domain);
  floor_config.name = "skyfuse-bench";
  const auto floor_timeout = std::chrono::milliseconds(120'000);
  for (int m : o.stations) {
    FloorResult floor;
    FloorResult all_to_all;
    RunSummary s;
    try {
      floor = measure_floor(floor_config, m, o.rounds, floor_timeout, FloorKind::kEcho);
      all_to_all = measure_floor(floor_config, m, o.rounds, floor_timeout, FloorKind::kAllToAll);
      s = run_for_bench(o, scenario, scenario_path, m, out);
    } catch (const RunAborted& e) {
      // An interrupt ends the bench with the rows measured so far on disk; one station count
      // failing (say, a machine too small for it) must not lose the others.
      if (transport::shutdown_requested()) {
        save_rows();
        fmt::print(
            "\n{} keeps what was measured before the interrupt ({} of {} station "
            "counts)\n",
            (out / "bench.json").string(), rows.size(), o.stations.size());
        throw;
      }
      fmt::print("{:>4} failed: {}\n", m, e.what());
      rows.push_back({{"stations", m}, {"rounds", o.rounds}, {"error", e.what()}});
      save_rows();
      continue;
    }

    rows.push_back(report_row(m, o.rounds, s, floor, all_to_all));
    save_rows();
  }
  save_rows();
  fmt::print("\nwrote {}\n", (out / "bench.json").string());
  return 0;
}

}  // namespace skyfuse::harness
