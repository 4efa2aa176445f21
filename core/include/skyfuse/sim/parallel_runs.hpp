#pragma once
/// \file
/// The one worker pool of the in-process Monte Carlo, for one aircraft's runs and many's: runs
/// handed out in order to a few threads, each run's result kept in its own slot so that the
/// figures reduced from them are the same bits whatever the thread count.

#include <functional>

namespace skyfuse {

/// The number of threads `threads` asks for: itself when positive, else one per core.
int worker_threads(int threads);

/// Runs fn(run) for run = 0..runs-1 on up to `threads` threads (the caller's among them); the
/// first exception any run throws is rethrown here once every worker has stopped, and no run
/// is started after it.
void parallel_runs(int runs, int threads, const std::function<void(int)>& fn);

}  // namespace skyfuse
