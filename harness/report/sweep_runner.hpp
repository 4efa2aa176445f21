#pragma once
// The sweep's work: Monte-Carlo runs of both architectures for M = 1..M_max stations at every
// speed the scenario lists, with a progress line. `skyfuse sweep` and `skyfuse reproduce
// paper000` both run it.

#include <vector>

#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/sim/monte_carlo.hpp"
#include "skyfuse/sim/picture_run.hpp"
#include "skyfuse/traffic/target_truth.hpp"

namespace skyfuse::harness {

/// Rows in speed order, then M = 1..max_stations; `threads` 0 means one per core.
std::vector<MonteCarloSummary> run_sweep_rows(const Scenario& scenario, int runs, int max_stations,
                                              int threads);

/// `runs` Monte-Carlo runs of a scenario with many aircraft (its picture, the first
/// `stations` stations), on `threads` workers (0: one per core); results in run order, the
/// same whatever the thread count.
std::vector<PictureRunResult> run_picture_runs(const Scenario& scenario,
                                               const std::vector<TargetTruth>& truth, int runs,
                                               int stations, int threads);

/// The largest RMSE of either architecture over the rows with at least `min_stations`
/// stations; 0 when there is none.
double worst_rmse(const std::vector<MonteCarloSummary>& rows, int min_stations);

}  // namespace skyfuse::harness
