#include "scale/scale_bench.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <thread>

#include "report/json_values.hpp"
#include "report/output_files.hpp"
#include "run/bench_scenario.hpp"
#include "run/execute_run.hpp"
#include "run/round_samples.hpp"
#include "run/simulated_hosts.hpp"
#include "scale/picture_scale_bench.hpp"
#include "scale/scale_runs.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"

namespace skyfuse::harness {
namespace {

struct ScaleRow : ScaleRuns<RunSummary> {
  std::string exchange;
  int stations = 0;
  int hosts = 0;
};

nlohmann::json to_json(const ScaleRow& r, int fanout) {
  nlohmann::json row = {{"exchange", r.exchange},
                        {"stations", r.stations},
                        {"fanout", r.exchange == "tree" ? nlohmann::json(fanout) : nullptr},
                        {"hosts", r.hosts}};
  if (!r.error.empty()) {
    row["error"] = r.error;
    return row;
  }
  const RunSummary& s = *r.lockstep;
  row["lockstep"] = {{"rounds_per_s", s.rounds_per_s},
                     {"round_latency_ms_p50", s.round_latency_us_p50 / 1e3},
                     {"round_latency_ms_p99", s.round_latency_us_p99 / 1e3},
                     {"datagrams_received_per_round", number_or_null(s.datagrams_per_round)},
                     {"data_samples_per_round", samples_per_round(r.exchange, r.stations, fanout)},
                     {"cpu_ms_per_station_round", s.cpu_ms_per_station_round},
                     {"node_peak_resident_mib", s.node_peak_resident_mib},
                     {"discovery_s", s.discovery_s},
                     {"max_abs_diff_between_peers", s.max_abs_diff_between_peers},
                     {"max_abs_diff_central_vs_p2p", s.max_abs_diff_central_vs_p2p}};
  if (!r.realtime_error.empty()) row["realtime"] = {{"error", r.realtime_error}};
  if (r.realtime) {
    const RunSummary& t = *r.realtime;
    row["realtime"] = {{"deadline_ms", t.realtime_deadline_ms},
                       {"rounds_all_inputs_in_time", t.rounds_all_inputs_in_time},
                       {"track_age_ms_p50", t.track_age_ms_p50},
                       {"track_age_ms_p99", t.track_age_ms_p99},
                       {"datagrams_received_per_round", number_or_null(t.datagrams_per_round)},
                       {"cpu_ms_per_station_round", t.cpu_ms_per_station_round},
                       {"discovery_s", t.discovery_s}};
  }
  return row;
}

// A figure the run may not have (a real-time run that failed, a count that could not be
// read): "" in the CSV, `absent` in the table.
std::string maybe(const std::optional<double>& value, double scale, int decimals,
                  const char* absent = "") {
  return value ? fmt::format("{:.{}f}", *value * scale, decimals) : absent;
}

std::optional<double> realtime_figure(const ScaleRow& r, double RunSummary::*field) {
  if (!r.realtime) return std::nullopt;
  return (*r.realtime).*field;
}

std::optional<double> realtime_datagrams(const ScaleRow& r) {
  return r.realtime ? r.realtime->datagrams_per_round : std::nullopt;
}

std::string csv_of(const std::vector<ScaleRow>& rows, int fanout) {
  std::string csv =
      "exchange,stations,hosts,rounds_per_s,latency_ms_p50,datagrams_per_round,"
      "samples_per_round,cpu_ms_per_station_round,node_peak_mib,discovery_s,"
      "realtime_in_time,track_age_ms_p50,track_age_ms_p99,realtime_datagrams_per_round\n";
  for (const ScaleRow& r : rows) {
    if (!r.error.empty()) continue;
    const RunSummary& s = *r.lockstep;
    csv += fmt::format("{},{},{},{:.2f},{:.3f},{},{},{:.4f},{:.1f},{:.2f},{},{},{},{}\n",
                       r.exchange, r.stations, r.hosts, s.rounds_per_s,
                       s.round_latency_us_p50 / 1e3, maybe(s.datagrams_per_round, 1.0, 1),
                       samples_per_round(r.exchange, r.stations, fanout),
                       s.cpu_ms_per_station_round, s.node_peak_resident_mib, s.discovery_s,
                       maybe(realtime_figure(r, &RunSummary::rounds_all_inputs_in_time), 1.0, 4),
                       maybe(realtime_figure(r, &RunSummary::track_age_ms_p50), 1.0, 2),
                       maybe(realtime_figure(r, &RunSummary::track_age_ms_p99), 1.0, 2),
                       maybe(realtime_datagrams(r), 1.0, 1));
  }
  return csv;
}

void print_header() {
  fmt::print("{:>5} {:>4} {:>5} {:>9} {:>7} {:>9} {:>7} {:>7} {:>7} {:>7} {:>8} {:>11} {:>9}\n",
             "exch.", "M", "hosts", "rounds/s", "p50 ms", "datagr.", "samples", "CPU ms", "peak MB",
             "disc. s", "in time", "age p50/99", "RT datagr.");
}

void print_row(const ScaleRow& r, int fanout) {
  if (!r.error.empty()) {
    fmt::print("{:>5} {:>4} failed: {}\n", r.exchange, r.stations, r.error);
    return;
  }
  const RunSummary& s = *r.lockstep;
  const std::string in_time =
      r.realtime_error.empty()
          ? maybe(realtime_figure(r, &RunSummary::rounds_all_inputs_in_time), 100.0, 1, "-")
          : "failed";
  const std::string age = r.realtime ? fmt::format("{:.1f}/{:.1f}", r.realtime->track_age_ms_p50,
                                                   r.realtime->track_age_ms_p99)
                                     : "-";
  fmt::print(
      "{:>5} {:>4} {:>5} {:>9.0f} {:>7.1f} {:>9} {:>7} {:>7.2f} {:>7.0f} {:>7.1f} {:>8} {:>11} "
      "{:>9}\n",
      r.exchange, r.stations, r.hosts, s.rounds_per_s, s.round_latency_us_p50 / 1e3,
      maybe(s.datagrams_per_round, 1.0, 0, "-"), samples_per_round(r.exchange, r.stations, fanout),
      s.cpu_ms_per_station_round, s.node_peak_resident_mib, s.discovery_s, in_time, age,
      maybe(realtime_datagrams(r), 1.0, 0, "-"));
  if (!r.realtime_error.empty()) fmt::print("      real-time run failed: {}\n", r.realtime_error);
}

RunSummary measure(const ScaleBenchOptions& o, const Scenario& scenario,
                   const std::string& scenario_path, const std::string& exchange, int m, int hosts,
                   bool realtime, const std::filesystem::path& out) {
  RunOptions run = scale_run_options(
      o, scenario_path, m, exchange, realtime,
      (out / fmt::format("{}-M{}-{}", exchange, m, realtime ? "realtime" : "lockstep")).string(),
      30.0);
  run.hosts = hosts;
  if (hosts > 0) run.discovery = o.host_discovery;
  return execute_run(run, make_run_plan(scenario, run.node.overrides));
}

}  // namespace

RunOptions scale_run_options(const ScaleBenchOptions& o, const std::string& scenario_path,
                             int stations, const std::string& exchange, bool realtime,
                             std::string out_dir, double round_timeout_s) {
  RunOptions run;
  run.node.scenario_path = scenario_path;
  run.node.overrides.stations = stations;
  run.node.overrides.steps = realtime ? o.realtime_steps : o.rounds;
  run.node.overrides.exchange = parse_exchange_kind(exchange);
  run.node.overrides.fanout = o.fanout;
  run.node.best_effort = o.best_effort;
  run.node.domain = o.domain;
  if (realtime) run.node.realtime_deadline_ms = o.realtime_deadline_ms;
  run.stations_per_process = o.stations_per_process;
  run.out_dir = std::move(out_dir);
  run.round_timeout_s = round_timeout_s;
  return run;
}

int run_scale_bench(const ScaleBenchOptions& o) {
  if (!o.aircraft.empty()) return run_picture_scale_bench(o);
  // Named variables, not a structured binding: the lambdas below capture them (clang 14 cannot
  // capture a binding).
  const BenchScenario bench = load_bench_scenario(o.scenario_path, "ring256.yaml", o.stations);
  const std::string& scenario_path = bench.path;
  const Scenario& scenario = bench.scenario;
  // Refused before anything runs, as the station counts are.
  for (int m : o.stations) {
    if (const int hosts = hosts_for(m); hosts > 0) {
      try {
        SimulatedHosts::check_allowed(hosts);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(fmt::format(
            "--stations: {} stations need {} simulated hosts, and {}", m, hosts, e.what()));
      }
    }
  }
  for (const std::string& e : o.exchanges) {
    if (!parse_exchange_kind(e)) {
      throw std::invalid_argument("--exchange: '" + e + "' is neither flat nor tree");
    }
  }

  const std::filesystem::path out(o.out_dir);
  std::filesystem::create_directories(out);
  fmt::print(
      "skyfuse bench --scale on {} cores: {} lock-step rounds and {} real-time steps ({} ms "
      "deadline) per run, tree fanout {}, {}, {} station(s) per process\n",
      std::thread::hardware_concurrency(), o.rounds, o.realtime_steps, o.realtime_deadline_ms,
      o.fanout, o.best_effort ? "best effort" : "reliable", o.stations_per_process);
  print_header();

  std::vector<ScaleRow> rows;
  // Rewritten after every row: a bench of an hour keeps what it measured if stopped.
  const auto save = [&] {
    nlohmann::json json_rows = nlohmann::json::array();
    for (const ScaleRow& r : rows) json_rows.push_back(to_json(r, o.fanout));
    const nlohmann::json doc = {{"cores", std::thread::hardware_concurrency()},
                                {"scenario", scenario.name},
                                {"rounds", o.rounds},
                                {"realtime_steps", o.realtime_steps},
                                {"best_effort", o.best_effort},
                                {"stations_per_process", o.stations_per_process},
                                {"rows", json_rows}};
    write_file_atomically(out / "scale.json", doc.dump(2) + "\n");
    write_file_atomically(out / "scale.csv", csv_of(rows, o.fanout));
  };
  for (int m : o.stations) {
    for (const std::string& exchange : o.exchanges) {
      ScaleRow row;
      row.exchange = exchange;
      row.stations = m;
      row.hosts = hosts_for(m);
      static_cast<ScaleRuns<RunSummary>&>(row) = measure_scale_runs<RunSummary>(
          o,
          [&](bool realtime) {
            return measure(o, scenario, scenario_path, exchange, m, row.hosts, realtime, out);
          },
          save);
      print_row(row, o.fanout);
      rows.push_back(std::move(row));
      save();
    }
  }
  const auto png = out / "scale.png";
  if (!run_plot_script("plot_scale.py", {(out / "scale.csv").string(), png.string()})) {
    fmt::print(stderr, "skyfuse: warning: could not draw {} (python3-matplotlib?)\n", png.string());
  }
  fmt::print("\nwrote {}, scale.csv and scale.png\n", (out / "scale.json").string());
  return 0;
}

}  // namespace skyfuse::harness
