#pragma once
// What both scale benchmarks (one aircraft: scale_bench.cpp; many: picture_scale_bench.cpp) do
// for each configuration they measure: a lock-step run and, when it ran, a real-time run of the
// same configuration, each with the options the bench gives every run. Only their columns
// differ.

#include <optional>
#include <string>

#include "run/run_aborted.hpp"
#include "run/run_options.hpp"
#include "scale/scale_bench.hpp"
#include "skyfuse/transport/shutdown.hpp"

namespace skyfuse::harness {

/// A configuration's runs: the lock-step one and the real-time one, or why either failed.
template <typename Summary>
struct ScaleRuns {
  std::optional<Summary> lockstep;
  std::optional<Summary> realtime;
  std::string error;           ///< the lock-step run failed: no figures at all
  std::string realtime_error;  ///< the real-time run failed: the lock-step figures stand
};

/// The options of one benchmark run of M = `stations` over `exchange` ("flat" or "tree"):
/// lock-step for `o.rounds` rounds or real time for `o.realtime_steps`, the bench's
/// reliability, domain, fanout and stations per process, its files in `out_dir`.
RunOptions scale_run_options(const ScaleBenchOptions& o, const std::string& scenario_path,
                             int stations, const std::string& exchange, bool realtime,
                             std::string out_dir, double round_timeout_s);

/// Measures a configuration: `measure(false)` (lock-step), then, if it ran and the bench has
/// real-time steps, `measure(true)`. One run failing (a machine too small for it) costs its own
/// figures only; an interrupt calls `save` (the rows measured so far) and ends the bench.
template <typename Summary, typename Measure, typename Save>
ScaleRuns<Summary> measure_scale_runs(const ScaleBenchOptions& o, const Measure& measure,
                                      const Save& save) {
  ScaleRuns<Summary> runs;
  const auto attempt = [&](bool realtime, std::optional<Summary>& into, std::string& error) {
    try {
      into = measure(realtime);
    } catch (const RunAborted& e) {
      if (transport::shutdown_requested()) {
        save();
        throw;
      }
      error = e.what();
    }
  };
  attempt(false, runs.lockstep, runs.error);
  if (runs.lockstep && o.realtime_steps > 0) attempt(true, runs.realtime, runs.realtime_error);
  return runs;
}

}  // namespace skyfuse::harness
