#pragma once
/// \file
/// Numerical outcome of a filter step. Failure is a value the caller reports with its own
/// context (station, step); it is never turned into NaN and never an assertion.

namespace skyfuse {

enum class NumericalStatus {
  kOk,
  /// A matrix that must be symmetric positive definite (innovation covariance, prior
  /// covariance, fused information matrix) failed its Cholesky factorisation.
  kNotPositiveDefinite,
  /// Fusion inputs were not in ascending station order, so peers could disagree bit-wise.
  kIncrementsOutOfOrder,
};

inline const char* to_string(NumericalStatus status) {
  switch (status) {
    case NumericalStatus::kOk:
      return "ok";
    case NumericalStatus::kNotPositiveDefinite:
      return "matrix not positive definite (Cholesky failed)";
    case NumericalStatus::kIncrementsOutOfOrder:
      return "increments not in ascending station order";
  }
  return "unknown";
}

}  // namespace skyfuse
