#include "report/sweep_runner.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
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

std::vector<PictureRunResult> run_picture_runs(const Scenario& scenario,
                                               const std::vector<TargetTruth>& truth, int runs,
                                               int stations, int threads) {
  const int workers = std::min(
      runs,
      threads > 0 ? threads : static_cast<int>(std::max(1U, std::thread::hardware_concurrency())));
  std::vector<PictureRunResult> results(static_cast<std::size_t>(runs));
  Progress progress("sweep", runs);
  progress.set_stage(fmt::format("picture of {} stations", stations));
  std::atomic<int> next{0};
  std::mutex lock;  // the progress line and the first failure
  std::exception_ptr failure;
  auto work = [&] {
    for (int r = next++; r < runs; r = next++) {
      try {
        results[static_cast<std::size_t>(r)] =
            run_picture(scenario, truth, stations, static_cast<std::uint64_t>(r));
      } catch (...) {
        const std::lock_guard<std::mutex> hold(lock);
        if (!failure) failure = std::current_exception();
        next = runs;  // the others stop after their run
        return;
      }
      const std::lock_guard<std::mutex> hold(lock);
      progress.advance();
    }
  };
  std::vector<std::thread> pool;
  for (int w = 1; w < workers; ++w) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
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
