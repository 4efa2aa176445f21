#include "scale/scale_bench.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <thread>

#include "report/json_values.hpp"
#include "report/output_files.hpp"
#include "run/bench_scenario.hpp"
#include "run/execute_run.hpp"
#include "run/picture_run.hpp"
#include "run/round_samples.hpp"
#include "run/simulated_hosts.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/sim/picture_plan.hpp"
#include "skyfuse/sim/run_kind.hpp"
#include "skyfuse/transport/shutdown.hpp"

namespace skyfuse::harness {
namespace {

// A configuration the bench measures: N aircraft (a picture's), M stations, an exchange, the
// simulated hosts M needs (one aircraft's: counts past one host's ports), and its two runs.
template <typename Summary>
struct ScaleRow {
  int aircraft = 0;
  int stations = 0;
  std::string exchange;  ///< "flat" or "tree"
  int hosts = 0;
  std::optional<Summary> lockstep;
  std::optional<Summary> realtime;
  std::string error;           ///< the lock-step run failed: no figures at all
  std::string realtime_error;  ///< the real-time run failed: the lock-step figures stand
};

// A figure the run may not have (a real-time run that failed, a count that could not be
// read): "" in the CSV, `absent` in the table.
std::string maybe(const std::optional<double>& value, double scale, int decimals,
                  const char* absent = "") {
  return value ? fmt::format("{:.{}f}", *value * scale, decimals) : absent;
}

// What the house measured of either kind's run, as both kinds' rows name it.
nlohmann::json house_figures(const RunFigures& s) {
  return {{"rounds_per_s", s.rounds_per_s},
          {"datagrams_received_per_round", number_or_null(s.datagrams_per_round)},
          {"cpu_ms_per_station_round", s.cpu_ms_per_station_round},
          {"node_peak_resident_mib", s.node_peak_resident_mib},
          {"discovery_s", s.discovery_s}};
}

// One aircraft's columns: latency, the data samples a round must deliver, the agreement of the
// peers and the center; in real time, the share of rounds with every input in time and the
// tracks' age. Files scale.json, scale.csv and scale.png.
struct OneAircraft {
  using Summary = RunSummary;
  using Row = ScaleRow<Summary>;
  static constexpr const char* kDefaultScenario = "ring256.yaml";
  static constexpr const char* kFiles = "scale";
  static constexpr double kRoundTimeoutS = 30.0;
  int fanout = 0;

  static std::optional<double> realtime_figure(const Row& r, double RunSummary::*field) {
    if (!r.realtime) return std::nullopt;
    return (*r.realtime).*field;
  }
  static std::optional<double> realtime_datagrams(const Row& r) {
    return r.realtime ? r.realtime->datagrams_per_round : std::nullopt;
  }

  // The row's configuration, and its own figures beside the house's (row_json).
  nlohmann::json configuration(const Row& r) const {
    return {{"exchange", r.exchange},
            {"stations", r.stations},
            {"fanout", r.exchange == "tree" ? nlohmann::json(fanout) : nullptr},
            {"hosts", r.hosts}};
  }
  nlohmann::json lockstep_figures(const Row& r) const {
    const RunSummary& s = *r.lockstep;
    return {{"round_latency_ms_p50", s.round_latency_us_p50 / 1e3},
            {"round_latency_ms_p99", s.round_latency_us_p99 / 1e3},
            {"data_samples_per_round", samples_per_round(r.exchange, r.stations, fanout)},
            {"max_abs_diff_between_peers", s.max_abs_diff_between_peers},
            {"max_abs_diff_central_vs_p2p", s.max_abs_diff_central_vs_p2p}};
  }
  static nlohmann::json realtime_figures(const RunSummary& t) {
    return {{"deadline_ms", t.realtime_deadline_ms},
            {"rounds_all_inputs_in_time", t.rounds_all_inputs_in_time},
            {"track_age_ms_p50", t.track_age_ms_p50},
            {"track_age_ms_p99", t.track_age_ms_p99}};
  }

  static std::string csv_header() {
    return "exchange,stations,hosts,rounds_per_s,latency_ms_p50,datagrams_per_round,"
           "samples_per_round,cpu_ms_per_station_round,node_peak_mib,discovery_s,"
           "realtime_in_time,track_age_ms_p50,track_age_ms_p99,realtime_datagrams_per_round\n";
  }
  std::string csv(const Row& r) const {
    const RunSummary& s = *r.lockstep;
    return fmt::format("{},{},{},{:.2f},{:.3f},{},{},{:.4f},{:.1f},{:.2f},{},{},{},{}\n",
                       r.exchange, r.stations, r.hosts, s.rounds_per_s,
                       s.round_latency_us_p50 / 1e3, maybe(s.datagrams_per_round, 1.0, 1),
                       samples_per_round(r.exchange, r.stations, fanout),
                       s.cpu_ms_per_station_round, s.node_peak_resident_mib, s.discovery_s,
                       maybe(realtime_figure(r, &RunSummary::rounds_all_inputs_in_time), 1.0, 4),
                       maybe(realtime_figure(r, &RunSummary::track_age_ms_p50), 1.0, 2),
                       maybe(realtime_figure(r, &RunSummary::track_age_ms_p99), 1.0, 2),
                       maybe(realtime_datagrams(r), 1.0, 1));
  }

  static void print_header() {
    fmt::print("{:>5} {:>4} {:>5} {:>9} {:>7} {:>9} {:>7} {:>7} {:>7} {:>7} {:>8} {:>11} {:>9}\n",
               "exch.", "M", "hosts", "rounds/s", "p50 ms", "datagr.", "samples", "CPU ms",
               "peak MB", "disc. s", "in time", "age p50/99", "RT datagr.");
  }
  static void print_failed(const Row& r) {
    fmt::print("{:>5} {:>4} failed: {}\n", r.exchange, r.stations, r.error);
  }
  void print(const Row& r) const {
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
        maybe(s.datagrams_per_round, 1.0, 0, "-"),
        samples_per_round(r.exchange, r.stations, fanout), s.cpu_ms_per_station_round,
        s.node_peak_resident_mib, s.discovery_s, in_time, age,
        maybe(realtime_datagrams(r), 1.0, 0, "-"));
  }

  static std::string run_dir(const Row& r, bool realtime) {
    return fmt::format("{}-M{}-{}", r.exchange, r.stations, realtime ? "realtime" : "lockstep");
  }
  static Summary execute(const RunOptions& run, const BenchScenario& bench) {
    return execute_run(run, make_run_plan(bench.scenario, run.node.overrides));
  }
};

// Many aircraft's columns: the pictures' agreement; in real time, the share of rounds with every
// scan fused in time. Files picture_scale.json and picture_scale.csv.
struct ManyAircraft {
  using Summary = PictureRunSummary;
  using Row = ScaleRow<Summary>;
  static constexpr const char* kDefaultScenario = "uam-metro.yaml";
  static constexpr const char* kFiles = "picture_scale";
  static constexpr double kRoundTimeoutS = 60.0;

  static double share_in_time(const PictureRunSummary& s) {
    return s.steps == 0 ? 0.0 : static_cast<double>(s.rounds_in_time) / s.steps;
  }

  static nlohmann::json configuration(const Row& r) {
    return {{"aircraft", r.aircraft}, {"stations", r.stations}, {"exchange", r.exchange}};
  }
  static nlohmann::json lockstep_figures(const Row& r) {
    const PictureRunSummary& s = *r.lockstep;
    return {{"peers_identical", s.peers_identical},
            {"equals_in_process", s.equals_in_process},
            {"max_state_gap_center_vs_p2p", s.max_state_gap_center_vs_p2p},
            {"confirmed_at_end", s.confirmed_at_end}};
  }
  static nlohmann::json realtime_figures(const PictureRunSummary& t) {
    return {{"rounds_in_time", t.rounds_in_time},
            {"steps", t.steps},
            {"share_in_time", share_in_time(t)},
            {"rounds_peers_apart", t.rounds_peers_apart}};
  }

  static std::string csv_header() {
    return "aircraft,stations,exchange,rounds_per_s,datagrams_per_round,cpu_ms_per_station_round,"
           "peers_identical,realtime_share_in_time,realtime_cpu_ms_per_station_round\n";
  }
  static std::string csv(const Row& r) {
    const PictureRunSummary& s = *r.lockstep;
    return fmt::format(
        "{},{},{},{:.2f},{},{:.4f},{},{},{}\n", r.aircraft, r.stations, r.exchange, s.rounds_per_s,
        maybe(s.datagrams_per_round, 1.0, 1), s.cpu_ms_per_station_round, s.peers_identical ? 1 : 0,
        r.realtime ? fmt::format("{:.4f}", share_in_time(*r.realtime)) : "",
        r.realtime ? fmt::format("{:.4f}", r.realtime->cpu_ms_per_station_round) : "");
  }

  static void print_header() {
    fmt::print("{:>5} {:>4} {:>5} {:>9} {:>9} {:>8} {:>10} {:>9} {:>10}\n", "N", "M", "exch.",
               "rounds/s", "datagr.", "CPU ms", "pictures", "in time", "RT CPU ms");
  }
  static void print_failed(const Row& r) {
    fmt::print("{:>5} {:>4} {:>5} failed: {}\n", r.aircraft, r.stations, r.exchange, r.error);
  }
  static void print(const Row& r) {
    const PictureRunSummary& s = *r.lockstep;
    const std::string in_time = r.realtime
                                    ? fmt::format("{:.1f} %", 100.0 * share_in_time(*r.realtime))
                                    : (r.realtime_error.empty() ? "-" : "failed");
    fmt::print("{:>5} {:>4} {:>5} {:>9.0f} {:>9} {:>8.2f} {:>10} {:>9} {:>10}\n", r.aircraft,
               r.stations, r.exchange, s.rounds_per_s, maybe(s.datagrams_per_round, 1.0, 0, "-"),
               s.cpu_ms_per_station_round, s.peers_identical ? "identical" : "apart", in_time,
               r.realtime ? fmt::format("{:.2f}", r.realtime->cpu_ms_per_station_round) : "-");
  }

  static std::string run_dir(const Row& r, bool realtime) {
    return fmt::format("N{}-M{}-{}-{}", r.aircraft, r.stations, r.exchange,
                       realtime ? "realtime" : "lockstep");
  }
  static Summary execute(const RunOptions& run, const BenchScenario& bench) {
    return execute_picture_run(run, make_picture_plan(bench.scenario, run.node.overrides));
  }
};

// A row of either kind in its JSON: the kind's configuration, the error of a run that failed,
// and each run's figures, the house's (house_figures) and the kind's own.
template <typename Kind>
nlohmann::json row_json(const Kind& kind, const typename Kind::Row& r) {
  nlohmann::json row = kind.configuration(r);
  if (!r.error.empty()) row["error"] = r.error;
  if (r.lockstep) {
    row["lockstep"] = house_figures(*r.lockstep);
    row["lockstep"].update(kind.lockstep_figures(r));
  }
  if (!r.realtime_error.empty()) row["realtime"] = {{"error", r.realtime_error}};
  if (r.realtime) {
    row["realtime"] = house_figures(*r.realtime);
    row["realtime"].update(kind.realtime_figures(*r.realtime));
  }
  return row;
}

// The options of one run of `row`'s configuration: lock-step for `o.rounds` rounds or real
// time for `o.realtime_steps`, the bench's reliability, domain, fanout and stations per
// process, its files in `out_dir`.
template <typename Row>
RunOptions run_options(const ScaleBenchOptions& o, const std::string& scenario_path, const Row& row,
                       bool realtime, std::string out_dir, double round_timeout_s) {
  RunOptions run;
  run.node.scenario_path = scenario_path;
  run.node.overrides.stations = row.stations;
  run.node.overrides.steps = realtime ? o.realtime_steps : o.rounds;
  run.node.overrides.exchange = parse_exchange_kind(row.exchange);
  run.node.overrides.fanout = o.fanout;
  if (row.aircraft > 0) run.node.overrides.aircraft = row.aircraft;
  run.node.best_effort = o.best_effort;
  run.node.domain = o.domain;
  if (realtime) run.node.realtime_deadline_ms = o.realtime_deadline_ms;
  run.stations_per_process = o.stations_per_process;
  run.hosts = row.hosts;
  if (row.hosts > 0) run.discovery = o.host_discovery;
  run.out_dir = std::move(out_dir);
  run.round_timeout_s = round_timeout_s;
  return run;
}

// The bench of either kind: for each configuration a lock-step run and, when it ran and the
// bench has real-time steps, a real-time one. One run failing (a machine too small for it)
// costs its own figures only; the rows are rewritten after each run, and an interrupt saves
// them and ends the bench.
template <typename Kind>
void measure_rows(const ScaleBenchOptions& o, const Kind& kind, const BenchScenario& bench,
                  const std::vector<int>& aircraft, const std::filesystem::path& out) {
  using Row = typename Kind::Row;
  Kind::print_header();
  std::vector<Row> rows;
  const auto save = [&] {
    nlohmann::json json_rows = nlohmann::json::array();
    std::string csv = Kind::csv_header();
    for (const Row& r : rows) {
      json_rows.push_back(row_json(kind, r));
      if (r.lockstep) csv += kind.csv(r);
    }
    const nlohmann::json doc = {{"cores", std::thread::hardware_concurrency()},
                                {"scenario", bench.scenario.name},
                                {"rounds", o.rounds},
                                {"realtime_steps", o.realtime_steps},
                                {"realtime_deadline_ms", o.realtime_deadline_ms},
                                {"best_effort", o.best_effort},
                                {"fanout", o.fanout},
                                {"stations_per_process", o.stations_per_process},
                                {"rows", json_rows}};
    write_file_atomically(out / fmt::format("{}.json", Kind::kFiles), doc.dump(2) + "\n");
    write_file_atomically(out / fmt::format("{}.csv", Kind::kFiles), csv);
  };
  const auto attempt = [&](const Row& row, bool realtime,
                           std::optional<typename Kind::Summary>& into, std::string& error) {
    try {
      const std::string dir = (out / Kind::run_dir(row, realtime)).string();
      into = Kind::execute(run_options(o, bench.path, row, realtime, dir, Kind::kRoundTimeoutS),
                           bench);
    } catch (const RunAborted& e) {
      if (transport::shutdown_requested()) {
        save();
        throw;
      }
      error = e.what();
    }
  };
  for (const int n : aircraft) {
    for (const int m : o.stations) {
      for (const std::string& exchange : o.exchanges) {
        Row row;
        row.aircraft = n;
        row.stations = m;
        row.exchange = exchange;
        if (n == 0) row.hosts = hosts_for(m);
        attempt(row, false, row.lockstep, row.error);
        if (row.lockstep && o.realtime_steps > 0) {
          attempt(row, true, row.realtime, row.realtime_error);
        }
        if (row.lockstep) {
          kind.print(row);
        } else {
          Kind::print_failed(row);
        }
        if (!row.realtime_error.empty()) {
          fmt::print("      real-time run failed: {}\n", row.realtime_error);
        }
        rows.push_back(std::move(row));
        save();
      }
    }
  }
}

}  // namespace

int run_scale_bench(const ScaleBenchOptions& o) {
  const bool many = !o.aircraft.empty();
  const BenchScenario bench = load_bench_scenario(
      o.scenario_path, many ? ManyAircraft::kDefaultScenario : OneAircraft::kDefaultScenario,
      o.stations);
  // Refused before anything runs, as the station counts are.
  const RunOf asked = many ? RunOf::kManyAircraft : RunOf::kOneAircraft;
  if (run_of(bench.scenario) != asked) {
    throw std::invalid_argument(
        many ? fmt::format("--aircraft: scenario '{}' has one target; give one with 'traffic' "
                           "(default scenarios/{})",
                           bench.scenario.name, ManyAircraft::kDefaultScenario)
             : fmt::format("--scale: scenario '{}' has many aircraft; give --aircraft N... to "
                           "measure them",
                           bench.scenario.name));
  }
  for (const int m : o.stations) {
    if (const int hosts = hosts_for(m); !many && hosts > 0) {
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
      "skyfuse bench --scale{} on {} cores, scenario '{}': {} lock-step rounds and {} real-time "
      "steps ({} ms deadline) per run, tree fanout {}, {}, {} station(s) per process\n",
      many ? " --aircraft" : "", std::thread::hardware_concurrency(), bench.scenario.name, o.rounds,
      o.realtime_steps, o.realtime_deadline_ms, o.fanout,
      o.best_effort ? "best effort" : "reliable", o.stations_per_process);
  if (many) {
    measure_rows(o, ManyAircraft{}, bench, o.aircraft, out);
    fmt::print("\nwrote {} and picture_scale.csv\n", (out / "picture_scale.json").string());
    return 0;
  }
  measure_rows(o, OneAircraft{o.fanout}, bench, {0}, out);
  const auto png = out / "scale.png";
  if (!run_plot_script("plot_scale.py", {(out / "scale.csv").string(), png.string()})) {
    fmt::print(stderr, "skyfuse: warning: could not draw {} (python3-matplotlib?)\n", png.string());
  }
  fmt::print("\nwrote {}, scale.csv and scale.png\n", (out / "scale.json").string());
  return 0;
}

}  // namespace skyfuse::harness
