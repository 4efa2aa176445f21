#include "skyfuse/sim/soak.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "skyfuse/scenario/truth.hpp"
#include "skyfuse/sim/monte_carlo.hpp"
#include "skyfuse/validation/sample_checks.hpp"

namespace skyfuse {

SoakReport soak(const Scenario& base, int stations, std::int64_t steps) {
  if (steps < 1) throw std::invalid_argument("soak: steps must be >= 1");
  Scenario scenario = base;
  scenario.steps = static_cast<int>(steps);
  const TruthTrajectory truth = generate_truth(scenario.target, scenario.target.speeds_mps.front(),
                                               scenario.time_step_s, scenario.steps);
  SoakReport report;
  report.steps = steps;
  report.min_diagonal = std::numeric_limits<double>::infinity();
  double window_sum = 0.0;
  const std::int64_t window_start = std::max<std::int64_t>(0, steps - 1000);
  // A factorisation that fails inside a filter step ends the run with a NumericalError that
  // names the step (and the station, for an increment); it is the soak's finding, not a crash.
  try {
    simulate_run(scenario, truth, stations, 0, [&](const StepRecord& r) {
      bool bad = false;
      for (const auto& [name, state] :
           {std::pair{"central", &r.central}, std::pair{"peer-to-peer", &r.decentralised}}) {
        if (const auto problem = check_estimate(state->mean, state->covariance)) {
          bad = true;
          if (!report.first_problem) {
            report.first_problem =
                fmt::format("step {}, {}: posterior {}", r.step, name, to_string(*problem));
          }
          continue;
        }
        report.min_diagonal =
            std::min(report.min_diagonal, state->covariance.diagonal().minCoeff());
      }
      if (bad) ++report.bad_steps;
      if (r.step >= window_start) {
        window_sum += (r.truth.head<3>() - r.position_p2p).squaredNorm();
      }
    });
  } catch (const NumericalError& e) {
    ++report.bad_steps;
    if (!report.first_problem) report.first_problem = e.what();
  }
  report.final_rmse_window_m = std::sqrt(window_sum / static_cast<double>(steps - window_start));
  return report;
}

}  // namespace skyfuse
