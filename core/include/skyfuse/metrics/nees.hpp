#pragma once
/// \file
/// Normalised estimation error squared: e^T P^-1 e with e = x_true - x_hat. For a consistent
/// filter it is chi^2 with N degrees of freedom.

#include <Eigen/Cholesky>
#include <limits>

#include "skyfuse/core/small_cholesky.hpp"
#include "skyfuse/core/types.hpp"

namespace skyfuse {

/// NaN when P is not positive definite, so a broken covariance cannot hide in an average.
template <int N>
double nees(const Vector<N>& truth, const GaussianState<N>& estimate) {
  SmallCholesky<N> factor;
  if (!factor.compute(estimate.covariance)) return std::numeric_limits<double>::quiet_NaN();
  const Vector<N> error = truth - estimate.mean;
  return error.dot(factor.solve(error));
}

}  // namespace skyfuse
