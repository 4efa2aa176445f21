#include "skyfuse/sim/monte_carlo.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <span>

#include "sim/configured_runs.hpp"
#include "skyfuse/registry/filter_info.hpp"
#include "skyfuse/registry/filter_shards.hpp"
#include "skyfuse/registry/part_info.hpp"
#include "skyfuse/registry/sensor_parts.hpp"
#include "skyfuse/sim/parallel_runs.hpp"

namespace skyfuse {

namespace {

// The runs of the scenario's configuration, from the shard that compiled its filter part.
std::vector<RunTrace> simulate_configured_runs(const Scenario& scenario,
                                               const TruthTrajectory& truth,
                                               std::span<const int> station_counts,
                                               std::uint64_t run, const NisGate& gate,
                                               const StepObserver& observer = {}) {
  const int most = *std::max_element(station_counts.begin(), station_counts.end());
  return with_filter_shard(scenario.filter, [&](auto shard) {
    return with_sensor_part<kSensorPartsOf<decltype(shard)::value>>(scenario, most, [&](auto part) {
      return simulate_configured_runs_in_shard<decltype(shard)::value, decltype(part)::value>(
          scenario, truth, station_counts, run, gate, observer);
    });
  });
}

// Degrees of freedom of the NEES (the state) and of the stacked NIS (the first M stations'
// measured components together).
struct Dof {
  int state = 0;
  int measurement = 0;
};
Dof dof_of(const Scenario& scenario, int stations) {
  const int filter_dof = find_filter(scenario.filter)->nees_dof;
  Dof dof{filter_dof != 0 ? filter_dof
                          : find_motion_model(scenario.filter.motion_model.kind)->state_dim,
          0};
  for (int i = 0; i < stations; ++i) {
    dof.measurement +=
        find_sensor(scenario.stations[static_cast<std::size_t>(i)].sensor.kind)->measurement_dim;
  }
  return dof;
}

void check_station_count(const Scenario& scenario, int stations) {
  if (stations < 1 || stations > static_cast<int>(scenario.stations.size())) {
    throw std::invalid_argument(
        fmt::format("stations must be in [1, {}], got {}", scenario.stations.size(), stations));
  }
}

}  // namespace

RunTrace simulate_run(const Scenario& scenario, const TruthTrajectory& truth, int stations,
                      std::uint64_t run, const StepObserver& observer, const NisGate& gate) {
  check_station_count(scenario, stations);
  const int counts[] = {stations};
  return std::move(simulate_configured_runs(scenario, truth, counts, run, gate, observer).front());
}

namespace {

// Reduces one station count's traces in run order: the same bits whatever the thread count.
MonteCarloSummary summarise(const std::vector<RunTrace>& traces, int stations, double speed_mps,
                            int steps_in_run, Dof dof) {
  MonteCarloSummary s;
  s.stations = stations;
  s.speed_mps = speed_mps;
  s.runs = static_cast<int>(traces.size());
  s.steps = steps_in_run;
  s.anees_band = average_chi_square_band(dof.state, s.runs);
  const auto steps = static_cast<std::size_t>(steps_in_run);
  double sum_sq_central = 0.0;
  double sum_sq_p2p = 0.0;
  double sum_nis = 0.0;
  for (const RunTrace& t : traces) {
    for (std::size_t k = 0; k < steps; ++k) {
      sum_sq_central += t.sq_error_central[k];
      sum_sq_p2p += t.sq_error_p2p[k];
      sum_nis += t.nis_central[k];
    }
    s.max_abs_diff_m = std::max(s.max_abs_diff_m, t.max_abs_diff_m);
  }
  double sum_anees = 0.0;
  int in_band = 0;
  for (std::size_t k = 0; k < steps; ++k) {
    double sum = 0.0;
    for (const RunTrace& t : traces) sum += t.nees_p2p[k];
    const double anees_k = sum / s.runs;
    sum_anees += anees_k;
    if (s.anees_band.contains(anees_k)) ++in_band;
  }
  const double samples = static_cast<double>(s.runs) * static_cast<double>(steps);
  s.rmse_central_m = std::sqrt(sum_sq_central / samples);
  s.rmse_p2p_m = std::sqrt(sum_sq_p2p / samples);
  s.anees = sum_anees / static_cast<double>(steps);
  s.anees_steps_in_band = in_band / static_cast<double>(steps);
  s.anis_per_dof = sum_nis / samples / static_cast<double>(dof.measurement);
  return s;
}

}  // namespace

std::vector<MonteCarloSummary> run_monte_carlo(const Scenario& scenario,
                                               const MonteCarloSettings& settings,
                                               const std::function<void()>& on_run_done) {
  if (settings.stations.empty()) throw std::invalid_argument("no station count given");
  for (int m : settings.stations) check_station_count(scenario, m);
  if (settings.runs < 1) throw std::invalid_argument("runs must be >= 1");

  const TruthTrajectory truth =
      generate_truth(scenario.target, settings.speed_mps, scenario.time_step_s, scenario.steps);
  // by_count[c][run]: the trace of station count c in run `run`.
  std::vector<std::vector<RunTrace>> by_count(
      settings.stations.size(), std::vector<RunTrace>(static_cast<std::size_t>(settings.runs)));
  std::mutex progress_mutex;
  parallel_runs(settings.runs, settings.threads, [&](int run) {
    std::vector<RunTrace> traces = simulate_configured_runs(
        scenario, truth, settings.stations, static_cast<std::uint64_t>(run), NisGate{});
    for (std::size_t c = 0; c < traces.size(); ++c) {
      by_count[c][static_cast<std::size_t>(run)] = std::move(traces[c]);
    }
    if (on_run_done) {
      const std::lock_guard lock(progress_mutex);
      on_run_done();
    }
  });

  std::vector<MonteCarloSummary> summaries;
  for (std::size_t c = 0; c < by_count.size(); ++c) {
    summaries.push_back(summarise(by_count[c], settings.stations[c], settings.speed_mps,
                                  scenario.steps, dof_of(scenario, settings.stations[c])));
  }
  return summaries;
}

}  // namespace skyfuse
