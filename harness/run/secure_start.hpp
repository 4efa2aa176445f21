#pragma once
// `skyfuse run --secure`: how a secure run gets past discovery on Fast DDS 2.9.
//
// Measured here: when the harness, the center and four stations start with DDS-Security, about
// one start in three leaves a pair of participants that never finish authenticating, or whose
// endpoints match but never pass data (the first round then times out), for as long as one
// waits - 30 s were tried - with no error from Fast DDS. A fresh start of every process succeeds
// as often as the first. So a secure run spends --discovery-timeout in attempts of at most
// kSecureAttemptS each, and after an attempt that stalled like this starts every process again.

#include <spdlog/spdlog.h>

#include <algorithm>

#include "run/lockstep_driver.hpp"
#include "run/run_options.hpp"
#include "skyfuse/transport/shutdown.hpp"

namespace skyfuse::harness {

/// Long enough for a secure start on a loaded 2-core machine (about 1.4 s when it works).
inline constexpr double kSecureAttemptS = 6.0;

/// True if `aborted` says that the run stalled before its first round completed: discovery did
/// not complete (the harness's timeout, or a node's, seen as its status or its exit code), or
/// round 0 closed incomplete because some pair of processes never matched.
bool is_stalled_start(const RunAborted& aborted);

/// Returns run_once(o) for a run that is not secure or whose processes start elsewhere; for a
/// secure run, spends `discovery_s` in attempts of at most kSecureAttemptS, calling
/// run_once(attempt) again, every process started afresh, after an attempt that stalled.
template <typename RunOnce>
auto with_secure_restarts(const RunOptions& o, double discovery_s, RunOnce&& run_once) {
  if (!o.node.secure_dir || o.external) return run_once(o);
  RunOptions attempt = o;
  const double attempt_s = std::min(discovery_s, kSecureAttemptS);
  attempt.discovery_timeout_s = attempt_s;
  const int attempts = std::max(1, static_cast<int>(discovery_s / attempt_s));
  for (int i = 1;; ++i) {
    try {
      return run_once(attempt);
    } catch (const RunAborted& e) {
      if (i >= attempts || transport::shutdown_requested() || !is_stalled_start(e)) throw;
      spdlog::warn(
          "secure discovery did not complete ({}); starting every process again "
          "(attempt {} of {})",
          e.what(), i + 1, attempts);
    }
  }
}

}  // namespace skyfuse::harness
