#pragma once
// The x at which a monotone CDF reaches a probability, by bisection: what the chi-square and
// Student-t quantiles share (chi_square.cpp, run_mean_interval.cpp).

#include <algorithm>
#include <cmath>

namespace skyfuse::detail {

/// The x in [low, high] with cdf(x) = probability, to within `tolerance` × max(floor, |high|)
/// (a floor of 0: relative to the bracket's top; of 1: absolute near 0, where a quantile may
/// be 0), in at most 200 halvings; cdf must be non-decreasing and the bracket hold the
/// probability.
template <typename Cdf>
double bisect_monotone(Cdf cdf, double probability, double low, double high, double tolerance,
                       double floor) {
  for (int i = 0; i < 200 && high - low > tolerance * std::max(floor, std::fabs(high)); ++i) {
    const double mid = 0.5 * (low + high);
    (cdf(mid) < probability ? low : high) = mid;
  }
  return 0.5 * (low + high);
}

}  // namespace skyfuse::detail
