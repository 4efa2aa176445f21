#include "report/sweep_runner.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <mutex>

#include "report/progress.hpp"
#include "skyfuse/sim/parallel_runs.hpp"

namespace skyfuse::harness {

std::vector<MonteCarloSummary> run_sweep_rows(const Scenario& scenario, int runs, int max_stations,
                                              int threads) {
  const int workers = worker_threads(threads);
  // Runs outermost: one run simulates its measurements once for every M.
  std::vector<int> counts(static_cast<std::size_t>(max_stations));
  for (int m = 1; m <= max_stations; ++m) counts[static_cast<std::size_t>(m - 1)] = m;
  const long total = static_cast<long>(scenario.target.speeds_mps.size()) * runs;
  Progress progress("sweep", total);
  std::vector<MonteCarloSummary> rows;
  for (double speed : scenario.target.speeds_mps) {
    progress.set_stage(fmt::format("M=1..{} {:.0f} km/h", max_stations, speed * 3.6));
    const std::vector<MonteCarloSummary> per_m =
        run_monte_carlo(scenario, {counts, speed, runs, workers}, [&] { progress.advance(); });
    rows.insert(rows.end(), per_m.begin(), per_m.end());
  }
  progress.finish();
  return rows;
}

std::vector<PictureRunResult> run_picture_runs(const Scenario& scenario,
                                               const std::vector<TargetTruth>& truth, int runs,
                                               int stations, int threads) {
  std::vector<PictureRunResult> results(static_cast<std::size_t>(runs));
  Progress progress("sweep", runs);
  progress.set_stage(fmt::format("picture of {} stations", stations));
  std::mutex progress_line;
  parallel_runs(runs, worker_threads(threads), [&](int r) {
    results[static_cast<std::size_t>(r)] =
        run_picture(scenario, truth, stations, static_cast<std::uint64_t>(r));
    const std::lock_guard<std::mutex> hold(progress_line);
    progress.advance();
  });
  progress.finish();
  return results;
}

double worst_rmse(const std::vector<MonteCarloSummary>& rows, int min_stations) {
  double worst = 0.0;
  for (const MonteCarloSummary& r : rows) {
    if (r.stations >= min_stations) worst = std::max({worst, r.rmse_central_m, r.rmse_p2p_m});
  }
  return worst;
}

}  // namespace skyfuse::harness
