#pragma once
/// \file
/// How far a mean over independent Monte-Carlo runs can be trusted: Student's t distribution and
/// the confidence interval of the runs' mean, which needs nothing of the samples within a run
/// (why that matters for an ANEES: nees_over_runs.hpp).

#include <vector>

namespace skyfuse {

/// P(T <= t) for T ~ Student's t with `dof` degrees of freedom (dof > 0).
double student_t_cdf(double t, double dof);

/// The t with student_t_cdf(t, dof) = probability, for probability in (0, 1).
double student_t_quantile(double probability, double dof);

/// The mean of independent values and the two-sided interval mean ± t s / sqrt(n) that holds
/// their expectation with probability `confidence` (the values roughly normal: a mean over a
/// run of many samples is).
struct RunMeanInterval {
  double mean = 0.0;
  double lower = 0.0;  ///< -inf with fewer than two values: one run says nothing of the spread
  double upper = 0.0;  ///< +inf likewise
  double standard_deviation = 0.0;  ///< of the values (n - 1 in the denominator)
  bool contains(double value) const { return value >= lower && value <= upper; }
};

/// Throws std::invalid_argument for no values or a confidence outside (0, 1).
RunMeanInterval run_mean_interval(const std::vector<double>& values, double confidence = 0.95);

}  // namespace skyfuse
