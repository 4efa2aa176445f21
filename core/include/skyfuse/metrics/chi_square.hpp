#pragma once
/// \file
/// Chi-square distribution functions for consistency tests (NEES, NIS).

namespace skyfuse {

/// P(X <= x) for X ~ chi^2(dof).
double chi_square_cdf(double x, double dof);

/// The x with chi_square_cdf(x, dof) = probability, for probability in (0, 1).
double chi_square_quantile(double probability, double dof);

/// Two-sided acceptance band for the average of `samples` independent chi^2(dof) values
/// (Bar-Shalom's ANEES/ANIS test): [q_lo / samples, q_hi / samples] with q the quantiles of
/// chi^2(samples * dof) at (1 -+ confidence) / 2.
struct ChiSquareBand {
  double lower = 0.0;
  double upper = 0.0;
  bool contains(double value) const { return value >= lower && value <= upper; }
};
ChiSquareBand average_chi_square_band(int dof, int samples, double confidence = 0.95);

}  // namespace skyfuse
