#pragma once
/// \file
/// The chi-square gate on a single measurement (`--nis-gate P`): a measurement whose
/// normalised innovation squared against the receiver's prior,
///
///   NIS = nu^T S^-1 nu,  nu = z - h(x^-),  S = H P^- H^T + R,
///
/// exceeds the chi^2 quantile at probability P, with as many degrees of freedom as the sensor
/// measures components, is an outlier and is not fused. A station gates its own measurement
/// against the common prior, the center each measurement against its own: with equal priors
/// both refuse the same ones.

#include <array>
#include <limits>
#include <optional>

#include "skyfuse/core/small_cholesky.hpp"
#include "skyfuse/core/types.hpp"

namespace skyfuse {

/// NIS of `z` (noise R) from `sensor` against `prior`; nothing if S is not positive definite.
template <int N, typename Sensor>
std::optional<double> measurement_nis(const GaussianState<N>& prior, const Sensor& sensor,
                                      const Vector<Sensor::kMeasDim>& z,
                                      const Covariance<Sensor::kMeasDim>& noise) {
  constexpr int M = Sensor::kMeasDim;
  const Jacobian<M, N> h = sensor.jacobian(prior.mean);
  const Vector<M> innovation = sensor.residual(z, sensor.predict(prior.mean));
  const Covariance<M> s = h * prior.covariance * h.transpose() + noise;
  SmallCholesky<M> factor;
  if (!factor.compute(s)) return std::nullopt;
  return innovation.dot(factor.solve(innovation));
}

class NisGate {
 public:
  /// Sensors with up to this many components can be gated.
  static constexpr int kMaxDof = 16;

  /// No gate: every measurement passes.
  NisGate() { thresholds_.fill(std::numeric_limits<double>::infinity()); }
  /// Refuses a measurement whose NIS exceeds the chi^2(m) quantile at `probability` in (0, 1),
  /// m the sensor's number of components.
  static NisGate at_probability(double probability);

  bool enabled() const { return probability_ > 0.0; }
  /// The threshold for a sensor of `dof` components (infinite without a gate).
  double threshold(int dof) const { return thresholds_.at(static_cast<std::size_t>(dof)); }
  double probability() const { return probability_; }  ///< 0 when there is no gate
  /// True if the measurement must not be fused (an S that is not positive definite included).
  template <int N, typename Sensor>
  bool refuses(const GaussianState<N>& prior, const Sensor& sensor,
               const Vector<Sensor::kMeasDim>& z, const Covariance<Sensor::kMeasDim>& noise) const {
    static_assert(Sensor::kMeasDim <= kMaxDof, "raise NisGate::kMaxDof");
    if (!enabled()) return false;
    const std::optional<double> nis = measurement_nis(prior, sensor, z, noise);
    return !nis || *nis > threshold(Sensor::kMeasDim);
  }

 private:
  std::array<double, kMaxDof + 1> thresholds_;  // by degrees of freedom; [0] unused
  double probability_ = 0.0;
};

}  // namespace skyfuse
