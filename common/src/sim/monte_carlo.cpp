#include "skyfuse/sim/monte_carlo.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <thread>

#include "skyfuse/scenario/measurement_simulation.hpp"
#include "skyfuse/tracking/central_tracker.hpp"
#include "skyfuse/tracking/peer_tracker.hpp"

namespace skyfuse {

RunTrace simulate_run(const Scenario& scenario, const TruthTrajectory& truth, int stations,
                      std::uint64_t run, const StepObserver& observer) {
  const auto m = static_cast<std::size_t>(stations);
  const ConstantAcceleration3D motion(scenario.time_step_s, scenario.filter.process_noise);
  const GaussianState<9> initial = initial_estimate(scenario, truth.states.front(), run);
  CentralTracker central(motion, initial);
  PeerTracker peers(motion, initial);

  // Everything sized once per run: the step loop allocates nothing.
  std::vector<StationObservation9> observations(m);
  std::vector<Increment9> increments(m);
  std::vector<double> weights(m);
  for (std::size_t i = 0; i < m; ++i) {
    const StationConfig& station = scenario.stations[i];
    observations[i].station_id = station.id;
    observations[i].sensor = StationSensor(station.position_m);
    observations[i].noise = station_noise_covariance(scenario, station, run);
    weights[i] = station.weight;
  }
  // Fusion sums in ascending station id whatever order the scenario lists them in.
  std::vector<std::size_t> order(m);
  for (std::size_t i = 0; i < m; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return observations[a].station_id < observations[b].station_id;
  });
  std::vector<double> ordered_weights(m);
  for (std::size_t j = 0; j < m; ++j) ordered_weights[j] = weights[order[j]];

  const auto steps = static_cast<std::size_t>(scenario.steps);
  RunTrace trace;
  trace.sq_error_central.resize(steps);
  trace.sq_error_p2p.resize(steps);
  trace.nees_p2p.resize(steps);
  trace.nis_central.resize(steps);

  for (std::size_t k = 0; k < steps; ++k) {
    const Vector<9>& x = truth.states[k];
    for (std::size_t j = 0; j < m; ++j) {
      StationObservation9& obs = observations[order[j]];
      obs.z = simulate_measurement(obs.sensor, x.head<3>(), obs.noise, scenario.seed, run,
                                   obs.station_id, k);
      const NumericalStatus status =
          peers.make_increment(obs.station_id, obs.sensor, obs.z, obs.noise, increments[j]);
      if (status != NumericalStatus::kOk) {
        throw NumericalError(fmt::format("p2p: step {}, station {}: increment failed: {}", k,
                                         obs.station_id, to_string(status)));
      }
    }
    const UpdateReport central_report = central.update(observations);
    if (central_report.status != NumericalStatus::kOk) {
      throw NumericalError(fmt::format("central: step {}: stacked update failed: {}", k,
                                       to_string(central_report.status)));
    }
    const NumericalStatus fused = peers.fuse(increments, ordered_weights);
    if (fused != NumericalStatus::kOk) {
      throw NumericalError(fmt::format("p2p: step {}: fusion failed: {}", k, to_string(fused)));
    }

    const Vector3 p = x.head<3>();
    const Vector3 p_central = central.estimate().mean.head<3>();
    const Vector3 p_p2p = peers.estimate().mean.head<3>();
    trace.sq_error_central[k] = (p - p_central).squaredNorm();
    trace.sq_error_p2p[k] = (p - p_p2p).squaredNorm();
    // P^-1 is the fused information matrix the peers hold anyway: e^T Y e.
    const Vector<9> error = x - peers.estimate().mean;
    trace.nees_p2p[k] = error.dot(peers.information() * error);
    trace.nis_central[k] = central_report.nis;
    trace.max_abs_diff_m = std::max(trace.max_abs_diff_m, (p_central - p_p2p).norm());
    if (observer) {
      observer({static_cast<int>(k), x, central.estimate(), peers.estimate(), central_report.nis});
    }

    central.predict();
    peers.predict();
  }
  return trace;
}

namespace {

// Runs fn(run) for run = 0..runs-1 on up to `threads` threads; the first exception thrown by
// any run is rethrown here after all workers have stopped.
void parallel_runs(int runs, int threads, const std::function<void(int)>& fn) {
  std::atomic<int> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto worker = [&] {
    for (int run = next++; run < runs; run = next++) {
      try {
        fn(run);
      } catch (...) {
        const std::lock_guard lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        next = runs;  // stop handing out work
      }
    }
  };
  const int extra = std::clamp(threads, 1, std::max(runs, 1)) - 1;
  std::vector<std::thread> pool;
  pool.reserve(static_cast<std::size_t>(extra));
  for (int t = 0; t < extra; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace

MonteCarloSummary run_monte_carlo(const Scenario& scenario, const MonteCarloSettings& settings,
                                  const std::function<void()>& on_run_done) {
  if (settings.stations < 1 || settings.stations > static_cast<int>(scenario.stations.size())) {
    throw std::invalid_argument(fmt::format("stations must be in [1, {}], got {}",
                                            scenario.stations.size(), settings.stations));
  }
  if (settings.runs < 1) throw std::invalid_argument("runs must be >= 1");

  const TruthTrajectory truth =
      generate_truth(scenario.target, settings.speed_mps, scenario.time_step_s, scenario.steps);
  std::vector<RunTrace> traces(static_cast<std::size_t>(settings.runs));
  std::mutex progress_mutex;
  parallel_runs(settings.runs, settings.threads, [&](int run) {
    traces[static_cast<std::size_t>(run)] =
        simulate_run(scenario, truth, settings.stations, static_cast<std::uint64_t>(run));
    if (on_run_done) {
      const std::lock_guard lock(progress_mutex);
      on_run_done();
    }
  });

  // Reduce in run order: the same bits whatever the thread count.
  MonteCarloSummary s;
  s.stations = settings.stations;
  s.speed_mps = settings.speed_mps;
  s.runs = settings.runs;
  s.steps = scenario.steps;
  s.anees_band = average_chi_square_band(9, settings.runs);
  const auto steps = static_cast<std::size_t>(scenario.steps);
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
    const double anees_k = sum / settings.runs;
    sum_anees += anees_k;
    if (s.anees_band.contains(anees_k)) ++in_band;
  }
  const double samples = static_cast<double>(settings.runs) * static_cast<double>(steps);
  s.rmse_central_m = std::sqrt(sum_sq_central / samples);
  s.rmse_p2p_m = std::sqrt(sum_sq_p2p / samples);
  s.anees = sum_anees / static_cast<double>(steps);
  s.anees_steps_in_band = in_band / static_cast<double>(steps);
  s.anis_per_dof = sum_nis / samples / (3.0 * settings.stations);
  return s;
}

}  // namespace skyfuse
