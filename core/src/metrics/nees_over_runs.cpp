#include "skyfuse/metrics/nees_over_runs.hpp"

#include <stdexcept>
#include <vector>

namespace skyfuse {

std::optional<NeesOverRuns> nees_over_runs(std::span<const RunNees> runs) {
  NeesOverRuns summary;
  std::vector<double> per_run;
  double independent_variance = 0.0;
  for (const RunNees& run : runs) {
    if (run.samples == 0) continue;
    if (summary.dof != 0 && run.dof != summary.dof) {
      throw std::invalid_argument("nees_over_runs: runs of different degrees of freedom");
    }
    summary.dof = run.dof;
    summary.samples += run.samples;
    const double per_dof = run.anees / run.dof;
    per_run.push_back(per_dof);
    independent_variance += 2.0 * per_dof * per_dof / (run.dof * static_cast<double>(run.samples));
  }
  if (per_run.empty()) return std::nullopt;
  summary.runs = per_run.size();
  const ChiSquareBand band =
      average_chi_square_band(summary.dof, static_cast<int>(summary.samples));
  summary.pooled_band = {band.lower / summary.dof, band.upper / summary.dof};
  summary.over_runs = run_mean_interval(per_run);
  independent_variance /= static_cast<double>(per_run.size());
  const double sd = summary.over_runs.standard_deviation;
  summary.variance_over_independent = sd * sd / independent_variance;
  return summary;
}

}  // namespace skyfuse
