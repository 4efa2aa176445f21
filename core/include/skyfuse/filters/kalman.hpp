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

#include "skyfuse/core/llt_success.hpp"
#include "skyfuse/core/status.hpp"
#include "skyfuse/core/types.hpp"

namespace skyfuse {

/// What a measurement update reports besides the new state.
struct UpdateReport {
  NumericalStatus status = NumericalStatus::kOk;
  /// Normalised innovation squared nu^T S^-1 nu; chi^2 with kMeasDim degrees of freedom for a
  /// consistent filter. NaN when the update failed.
  double nis = std::numeric_limits<double>::quiet_NaN();
  /// log det S, the innovation covariance's; only update_with_likelihood fills it (its
  /// logarithms would cost more than the rest of a small update).
  double log_det_innovation = std::numeric_limits<double>::quiet_NaN();

  /// log N(nu; 0, S) = -(nis + log det S + m log 2 pi) / 2: the likelihood of the measurement,
  /// by which an IMM weighs its modes.
  double log_likelihood(int measurement_dim) const {
    constexpr double kLogTwoPi = 1.8378770664093454836;
    return -0.5 * (nis + log_det_innovation + measurement_dim * kLogTwoPi);
  }
};

/// Q, evaluated at the prior mean for a model whose noise depends on the state (one driven
/// along its heading, say).
template <int N, typename TransitionModel>
decltype(auto) process_noise_at(const TransitionModel& model, const Vector<N>& prior_mean) {
  if constexpr (requires { model.process_noise(prior_mean); }) {
    return model.process_noise(prior_mean);
  } else {
    return model.process_noise();
  }
}

/// Time update: x <- f(x), P <- F P F^T + Q with F evaluated at the prior mean. A model that
/// knows the structure of F may supply propagate_covariance(P) = F P F^T + Q itself.
template <int N, typename TransitionModel>
void predict(GaussianState<N>& state, const TransitionModel& model) {
  if constexpr (requires { model.propagate_covariance(state.covariance); }) {
    state.covariance = model.propagate_covariance(state.covariance);
  } else {
    const Covariance<N> f = model.jacobian(state.mean);
    const Covariance<N> fp = f.lazyProduct(state.covariance);
    state.covariance = fp.lazyProduct(f.transpose()) + process_noise_at<N>(model, state.mean);
  }
  state.mean = model.propagate(state.mean);
  symmetrize(state.covariance);
}

/// (I - K H) P (I - K H)^T + K R K^T where H is zero beyond its first C columns. Then
/// A = I - [KH 0] differs from I in those C columns only, and the two products skip exactly the
/// identity and zero parts:  A P = P - KH P[0:C, :],  (A P) A^T = A P - (A P)[:, 0:C] KH^T.
/// Small fixed sizes use coefficient-wise products, far cheaper than a blocked GEMM at 9 x 9.
template <int N, int C>
Covariance<N> joseph_without_noise(const Covariance<N>& p, const Matrix<N, C>& kh) {
  Covariance<N> ap = p;
  ap.noalias() -= kh.lazyProduct(p.template topRows<C>());
  Covariance<N> out = ap;
  out.noalias() -= ap.template leftCols<C>().lazyProduct(kh.transpose());
  return out;
}

template <int N, int C, int M>
Covariance<N> joseph_covariance(const Covariance<N>& p, const Matrix<N, C>& kh,
                                const Matrix<N, M>& gain, const Covariance<M>& noise) {
  Covariance<N> out = joseph_without_noise<N, C>(p, kh);
  const Matrix<N, M> kr = gain.lazyProduct(noise);
  out.noalias() += kr.lazyProduct(gain.transpose());
  return out;
}

namespace detail {

template <bool kWithLogDet, int N, typename Sensor>
UpdateReport update(GaussianState<N>& state, const Sensor& sensor,
                    const Vector<Sensor::kMeasDim>& z, const Covariance<Sensor::kMeasDim>& noise) {
  static_assert(Sensor::kStateDim == N, "sensor and state dimensions differ");
  constexpr int M = Sensor::kMeasDim;
  constexpr int C = jacobian_cols<Sensor>();

  const Matrix<M, C> h = sensor.jacobian(state.mean).template leftCols<C>();
  const Vector<M> innovation = sensor.residual(z, sensor.predict(state.mean));
  const Matrix<N, M> pht = state.covariance.template leftCols<C>().lazyProduct(h.transpose());
  const Covariance<M> s = h.lazyProduct(pht.template topRows<C>()) + noise;

  const Eigen::LLT<Covariance<M>> s_factor(s);
  if (!llt_succeeded(s_factor)) return {NumericalStatus::kNotPositiveDefinite};

  // K = P H^T S^-1, computed as (S^-1 H P)^T since S is symmetric.
  const Matrix<N, M> gain = s_factor.solve(pht.transpose()).transpose();
  state.mean += gain * innovation;
  state.covariance = joseph_covariance<N, C, M>(state.covariance, gain.lazyProduct(h), gain, noise);
  symmetrize(state.covariance);

  UpdateReport report{NumericalStatus::kOk, innovation.dot(s_factor.solve(innovation))};
  if constexpr (kWithLogDet) {
    report.log_det_innovation = 2.0 * s_factor.matrixLLT().diagonal().array().log().sum();
  }
  return report;
}

}  // namespace detail

/// Measurement update with the gain from a Cholesky solve of the innovation covariance (never
/// an explicit inverse) and the covariance in Joseph form, (I-KH) P (I-KH)^T + K R K^T, which
/// stays symmetric positive semi-definite even when the gain is not exactly optimal.
/// On failure the state is left unchanged.
template <int N, typename Sensor>
UpdateReport update(GaussianState<N>& state, const Sensor& sensor,
                    const Vector<Sensor::kMeasDim>& z, const Covariance<Sensor::kMeasDim>& noise) {
  return detail::update<false>(state, sensor, z, noise);
}

/// The same update, bit for bit, that also reports log det S, so that the report's
/// log_likelihood() is defined.
template <int N, typename Sensor>
UpdateReport update_with_likelihood(GaussianState<N>& state, const Sensor& sensor,
                                    const Vector<Sensor::kMeasDim>& z,
                                    const Covariance<Sensor::kMeasDim>& noise) {
  return detail::update<true>(state, sensor, z, noise);
}

}  // namespace skyfuse
