#pragma once
/// \file
/// The chi-square gate on a single measurement (`--nis-gate P`): a measurement whose
/// normalised innovation squared against the receiver's prior,
///
///   NIS = nu^T S^-1 nu,  nu = z - h(x^-),  S = H P^- H^T + R,
///
/// exceeds the chi^2(3) quantile at probability P is an outlier and is not fused. A station
/// gates its own measurement against the common prior, the center each measurement against its
/// own: with equal priors both refuse the same ones.

#include <limits>
#include <optional>

#include "skyfuse/core/types.hpp"
#include "skyfuse/scenario/measurement_simulation.hpp"

namespace skyfuse {

/// NIS of `z` (noise R) from `sensor` against `prior`; nothing if S is not positive definite.
std::optional<double> measurement_nis(const GaussianState<9>& prior, const StationSensor& sensor,
                                      const Vector3& z, const Covariance<3>& noise);

class NisGate {
 public:
  /// No gate: every measurement passes.
  NisGate() = default;
  /// Refuses a measurement whose NIS exceeds the chi^2(3) quantile at `probability` in (0, 1).
  static NisGate at_probability(double probability);

  bool enabled() const { return threshold_ < std::numeric_limits<double>::infinity(); }
  double threshold() const { return threshold_; }
  double probability() const { return probability_; }  ///< 0 when there is no gate
  /// True if the measurement must not be fused (an S that is not positive definite included).
  bool refuses(const GaussianState<9>& prior, const StationSensor& sensor, const Vector3& z,
               const Covariance<3>& noise) const;

 private:
  double threshold_ = std::numeric_limits<double>::infinity();
  double probability_ = 0.0;
};

}  // namespace skyfuse
