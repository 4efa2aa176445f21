#pragma once
/// \file
/// Extended Kalman filter steps, templated on the models so that one filter serves every
/// transition model and every sensor (a linear model is the special case whose Jacobian is
/// constant, so the same code is the plain Kalman filter).
///
/// A transition model provides `propagate(x)`, `jacobian(x)` (dF/dx) and `process_noise()`.
/// A sensor provides `predict(x)`, `jacobian(x)` (dh/dx), `residual(z, z_pred)` and the
/// constants `kStateDim`, `kMeasDim`; it travels with each measurement, so one filter can take
/// measurements from many stations.

#include <Eigen/Cholesky>
#include <limits>

#include "skyfuse/core/status.hpp"
#include "skyfuse/core/types.hpp"

namespace skyfuse {

/// What a measurement update reports besides the new state.
struct UpdateReport {
  NumericalStatus status = NumericalStatus::kOk;
  /// Normalised innovation squared nu^T S^-1 nu; chi^2 with kMeasDim degrees of freedom for a
  /// consistent filter. NaN when the update failed.
  double nis = std::numeric_limits<double>::quiet_NaN();
};

/// Time update: x <- f(x), P <- F P F^T + Q with F evaluated at the prior mean.
template <int N, typename TransitionModel>
void predict(GaussianState<N>& state, const TransitionModel& model) {
  const Covariance<N> f = model.jacobian(state.mean);
  state.mean = model.propagate(state.mean);
  Covariance<N> fp;
  fp.noalias() = f * state.covariance;
  state.covariance.noalias() = fp * f.transpose();
  state.covariance += model.process_noise();
  symmetrize(state.covariance);
}

/// Measurement update with the gain from a Cholesky solve of the innovation covariance (never
/// an explicit inverse) and the covariance in Joseph form, (I-KH) P (I-KH)^T + K R K^T, which
/// stays symmetric positive semi-definite even when the gain is not exactly optimal.
/// On failure the state is left unchanged.
template <int N, typename Sensor>
UpdateReport update(GaussianState<N>& state, const Sensor& sensor,
                    const Vector<Sensor::kMeasDim>& z, const Covariance<Sensor::kMeasDim>& noise) {
  static_assert(Sensor::kStateDim == N, "sensor and state dimensions differ");
  constexpr int M = Sensor::kMeasDim;

  const Jacobian<M, N> h = sensor.jacobian(state.mean);
  const Vector<M> innovation = sensor.residual(z, sensor.predict(state.mean));
  const Matrix<N, M> pht = state.covariance * h.transpose();
  const Covariance<M> s = h * pht + noise;

  const Eigen::LLT<Covariance<M>> s_factor(s);
  if (s_factor.info() != Eigen::Success)
    return {NumericalStatus::kNotPositiveDefinite};

  // K = P H^T S^-1, computed as (S^-1 H P)^T since S is symmetric.
  const Matrix<N, M> gain = s_factor.solve(pht.transpose()).transpose();
  state.mean += gain * innovation;

  Covariance<N> i_minus_kh = Covariance<N>::Identity();
  i_minus_kh.noalias() -= gain * h;
  Covariance<N> joseph;
  joseph.noalias() = i_minus_kh * state.covariance * i_minus_kh.transpose();
  joseph.noalias() += gain * noise * gain.transpose();
  state.covariance = joseph;
  symmetrize(state.covariance);

  return {NumericalStatus::kOk, innovation.dot(s_factor.solve(innovation))};
}

}  // namespace skyfuse
