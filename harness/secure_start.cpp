#include "secure_start.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <string_view>

#include "skyfuse/options/node_options.hpp"
#include "skyfuse/transport/shutdown.hpp"

namespace skyfuse::harness {

bool is_stalled_start(const RunAborted& aborted) {
  const std::string_view what = aborted.what();
  // The harness's timeout and a node's FAILED status both say so; a node that timed out first
  // may also be seen only by its exit code.
  const std::string node_exit =
      fmt::format("exited with status {}", static_cast<int>(options::kExitDiscoveryTimeout));
  return what.find("discovery timed out") != std::string_view::npos ||
         what.find(node_exit) != std::string_view::npos || what.starts_with("round 0 incomplete");
}

RunSummary execute_secure_run(const RunOptions& options, const RunPlan& plan) {
  // Processes started elsewhere cannot be started again from here.
  if (options.external) return execute_run(options, plan);
  RunOptions attempt = options;
  const double total_s = discovery_timeout_s(options, plan.stations);
  const double attempt_s = std::min(total_s, kSecureAttemptS);
  attempt.discovery_timeout_s = attempt_s;
  const int attempts = std::max(1, static_cast<int>(total_s / attempt_s));
  for (int i = 1;; ++i) {
    try {
      return execute_run(attempt, plan);
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
