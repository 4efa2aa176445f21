#include "report/sweep_runner.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <thread>

#include "report/progress.hpp"

namespace skyfuse::harness {

std::vector<MonteCarloSummary> run_sweep_rows(const Scenario& scenario, int runs, int max_stations,
                                              int threads) {
  const int workers =
      threads > 0 ? threads : static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
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

double worst_rmse(const std::vector<MonteCarloSummary>& rows, int min_stations) {
  double worst = 0.0;
  for (const MonteCarloSummary& r : rows) {
    if (r.stations >= min_stations) worst = std::max({worst, r.rmse_central_m, r.rmse_p2p_m});
  }
  return worst;
}

}  // namespace skyfuse::harness
