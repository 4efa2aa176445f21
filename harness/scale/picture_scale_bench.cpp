#include "scale/picture_scale_bench.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <thread>

#include "report/json_values.hpp"
#include "report/output_files.hpp"
#include "run/bench_scenario.hpp"
#include "run/picture_run.hpp"
#include "scale/scale_runs.hpp"

namespace skyfuse::harness {
namespace {

struct PictureScaleRow : ScaleRuns<PictureRunSummary> {
  int aircraft = 0;
  int stations = 0;
  std::string exchange;  ///< "flat" or "tree"
};

double share_in_time(const PictureRunSummary& s) {
  return s.steps == 0 ? 0.0 : static_cast<double>(s.rounds_in_time) / s.steps;
}

nlohmann::json to_json(const PictureScaleRow& r) {
  nlohmann::json row = {
      {"aircraft", r.aircraft}, {"stations", r.stations}, {"exchange", r.exchange}};
  if (!r.error.empty()) row["error"] = r.error;
  if (r.lockstep) {
    const PictureRunSummary& s = *r.lockstep;
    row["lockstep"] = {{"rounds_per_s", s.rounds_per_s},
                       {"datagrams_received_per_round", number_or_null(s.datagrams_per_round)},
                       {"cpu_ms_per_station_round", s.cpu_ms_per_station_round},
                       {"discovery_s", s.discovery_s},
                       {"peers_identical", s.peers_identical},
                       {"equals_in_process", s.equals_in_process},
                       {"max_state_gap_center_vs_p2p", s.max_state_gap_center_vs_p2p},
                       {"confirmed_at_end", s.confirmed_at_end}};
  }
  if (!r.realtime_error.empty()) row["realtime"] = {{"error", r.realtime_error}};
  if (r.realtime) {
    const PictureRunSummary& t = *r.realtime;
    row["realtime"] = {{"rounds_in_time", t.rounds_in_time},
                       {"steps", t.steps},
                       {"share_in_time", share_in_time(t)},
                       {"rounds_peers_apart", t.rounds_peers_apart},
                       {"datagrams_received_per_round", number_or_null(t.datagrams_per_round)},
                       {"cpu_ms_per_station_round", t.cpu_ms_per_station_round}};
  }
  return row;
}

std::string csv_of(const std::vector<PictureScaleRow>& rows) {
  std::string csv =
      "aircraft,stations,exchange,rounds_per_s,datagrams_per_round,cpu_ms_per_station_round,"
      "peers_identical,realtime_share_in_time,realtime_cpu_ms_per_station_round\n";
  for (const PictureScaleRow& r : rows) {
    if (!r.lockstep) continue;
    const PictureRunSummary& s = *r.lockstep;
    csv += fmt::format(
        "{},{},{},{:.2f},{},{:.4f},{},{},{}\n", r.aircraft, r.stations, r.exchange, s.rounds_per_s,
        s.datagrams_per_round ? fmt::format("{:.1f}", *s.datagrams_per_round) : "",
        s.cpu_ms_per_station_round, s.peers_identical ? 1 : 0,
        r.realtime ? fmt::format("{:.4f}", share_in_time(*r.realtime)) : "",
        r.realtime ? fmt::format("{:.4f}", r.realtime->cpu_ms_per_station_round) : "");
  }
  return csv;
}

void print_row(const PictureScaleRow& r) {
  if (!r.lockstep) {
    fmt::print("{:>5} {:>4} {:>5} failed: {}\n", r.aircraft, r.stations, r.exchange, r.error);
    return;
  }
  const PictureRunSummary& s = *r.lockstep;
  const std::string in_time = r.realtime
                                  ? fmt::format("{:.1f} %", 100.0 * share_in_time(*r.realtime))
                                  : (r.realtime_error.empty() ? "-" : "failed");
  fmt::print("{:>5} {:>4} {:>5} {:>9.0f} {:>9} {:>8.2f} {:>10} {:>9} {:>10}\n", r.aircraft,
             r.stations, r.exchange, s.rounds_per_s,
             s.datagrams_per_round ? fmt::format("{:.0f}", *s.datagrams_per_round) : "-",
             s.cpu_ms_per_station_round, s.peers_identical ? "identical" : "apart", in_time,
             r.realtime ? fmt::format("{:.2f}", r.realtime->cpu_ms_per_station_round) : "-");
  if (!r.realtime_error.empty()) fmt::print("      real-time run failed: {}\n", r.realtime_error);
}

PictureRunSummary measure(const ScaleBenchOptions& o, const BenchScenario& bench, int n, int m,
                          const std::string& exchange, bool realtime,
                          const std::filesystem::path& out) {
  RunOptions run = scale_run_options(
      o, bench.path, m, exchange, realtime,
      (out / fmt::format("N{}-M{}-{}-{}", n, m, exchange, realtime ? "realtime" : "lockstep"))
          .string(),
      60.0);
  run.node.overrides.aircraft = n;
  return execute_picture_run(run, make_picture_plan(bench.scenario, run.node.overrides));
}

}  // namespace

int run_picture_scale_bench(const ScaleBenchOptions& o) {
  const BenchScenario bench = load_bench_scenario(o.scenario_path, "uam-metro.yaml", o.stations);
  if (!bench.scenario.has_many_targets()) {
    throw std::invalid_argument("--aircraft: scenario '" + bench.scenario.name +
                                "' has one target; give one with 'traffic' (default "
                                "scenarios/uam-metro.yaml)");
  }
  for (const std::string& e : o.exchanges) {
    if (e != "flat" && e != "tree") {
      throw std::invalid_argument("--exchange: " + e + " not in {flat,tree}");
    }
  }
  const std::filesystem::path out(o.out_dir);
  std::filesystem::create_directories(out);
  fmt::print(
      "skyfuse bench --scale --aircraft on {} cores, scenario '{}': {} lock-step rounds and {} "
      "real-time steps ({} ms deadline) per run, the tree in clusters of {}, {}, {} station(s) "
      "per process\n",
      std::thread::hardware_concurrency(), bench.scenario.name, o.rounds, o.realtime_steps,
      o.realtime_deadline_ms, o.fanout, o.best_effort ? "best effort" : "reliable",
      o.stations_per_process);
  fmt::print("{:>5} {:>4} {:>5} {:>9} {:>9} {:>8} {:>10} {:>9} {:>10}\n", "N", "M", "exch.",
             "rounds/s", "datagr.", "CPU ms", "pictures", "in time", "RT CPU ms");

  std::vector<PictureScaleRow> rows;
  const auto save = [&] {
    nlohmann::json json_rows = nlohmann::json::array();
    for (const PictureScaleRow& r : rows) json_rows.push_back(to_json(r));
    const nlohmann::json doc = {{"cores", std::thread::hardware_concurrency()},
                                {"scenario", bench.scenario.name},
                                {"rounds", o.rounds},
                                {"realtime_steps", o.realtime_steps},
                                {"realtime_deadline_ms", o.realtime_deadline_ms},
                                {"best_effort", o.best_effort},
                                {"fanout", o.fanout},
                                {"stations_per_process", o.stations_per_process},
                                {"rows", json_rows}};
    write_file_atomically(out / "picture_scale.json", doc.dump(2) + "\n");
    write_file_atomically(out / "picture_scale.csv", csv_of(rows));
  };
  for (const int n : o.aircraft) {
    for (const int m : o.stations) {
      for (const std::string& exchange : o.exchanges) {
        PictureScaleRow row;
        row.aircraft = n;
        row.stations = m;
        row.exchange = exchange;
        static_cast<ScaleRuns<PictureRunSummary>&>(row) = measure_scale_runs<PictureRunSummary>(
            o, [&](bool realtime) { return measure(o, bench, n, m, exchange, realtime, out); },
            save);
        print_row(row);
        rows.push_back(std::move(row));
        save();
      }
    }
  }
  fmt::print("\nwrote {} and picture_scale.csv\n", (out / "picture_scale.json").string());
  return 0;
}

}  // namespace skyfuse::harness
