#pragma once
/// \file
/// Numerical hygiene over a long run: both architectures stepped for many steps on the
/// scenario's trajectory (flown on past its own length), with every posterior covariance
/// checked at every step.

#include <cstdint>
#include <optional>
#include <string>

#include "skyfuse/scenario/scenario.hpp"

namespace skyfuse {

struct SoakReport {
  std::int64_t steps = 0;
  /// Steps at which either architecture's posterior failed check_estimate: a NaN or Inf, an
  /// implausible magnitude, or a covariance not positive definite. (Symmetry needs no check:
  /// every filter step ends by symmetrising P.)
  std::int64_t bad_steps = 0;
  std::optional<std::string> first_problem;  ///< which step and architecture, and what
  double min_diagonal = 0.0;                 ///< smallest variance seen (> 0 when healthy)
  double final_rmse_window_m = 0.0;          ///< p2p position RMSE over the last 1000 steps
};

/// Runs `steps` steps with the first `stations` stations of `scenario`, Monte-Carlo run 0.
SoakReport soak(const Scenario& scenario, int stations, std::int64_t steps);

}  // namespace skyfuse
