#pragma once
/// \file
/// The information a single station's measurement adds to a common prior (paper 000, Sec. III,
/// decentralised scheme), computed directly instead of by the paper's inversions:
///
///   dQ_i = H_i^T R_i^-1 H_i
///   dy_i = H_i^T R_i^-1 (nu_i + H_i x^-),   nu_i = z_i - h_i(x^-)  (angles wrapped)
///
/// This equals the paper's (P_i^+)^-1 - (P^-)^-1 and (P_i^+)^-1 x_i^+ - (P^-)^-1 x^- exactly
/// in exact arithmetic (tests/unit/fusion/information_increment_test.cpp shows it numerically),
/// while needing only a 3x3 Cholesky of R_i instead of two N x N inversions.

#include "skyfuse/core/small_cholesky.hpp"
#include "skyfuse/core/status.hpp"
#include "skyfuse/core/types.hpp"

namespace skyfuse {

template <int N>
struct InformationIncrement {
  int station_id = 0;
  Covariance<N> delta_information = Covariance<N>::Zero();  ///< dQ_i
  Vector<N> delta_vector = Vector<N>::Zero();               ///< dy_i

  /// What a station sends for a measurement screened out: an increment that adds nothing, so
  /// that its peers need not wait for one.
  void set_zero(int station) {
    station_id = station;
    delta_information.setZero();
    delta_vector.setZero();
  }
};

/// What a station sends beside its increment so that its peers can form the likelihood of the
/// stacked measurement (fused_likelihood.hpp); all zero for a station whose measurement was
/// screened out (it adds nothing, like its zero increment).
struct LikelihoodTerms {
  double weighted_innovation = 0.0;  ///< nu_i^T R_i^-1 nu_i
  double log_det_noise = 0.0;        ///< log det R_i
  int measurement_dim = 0;           ///< m_i
};

namespace detail {

// The increment, and with kWithTerms the likelihood terms from the same factor of R and the
// same innovation. A compile-time choice: a run-time one slowed the station step by a fifth.
template <bool kWithTerms, int N, typename Sensor>
NumericalStatus compute_increment(int station_id, const GaussianState<N>& prior,
                                  const Sensor& sensor, const Vector<Sensor::kMeasDim>& z,
                                  const Covariance<Sensor::kMeasDim>& noise,
                                  InformationIncrement<N>& out, LikelihoodTerms* terms) {
  static_assert(Sensor::kStateDim == N, "sensor and state dimensions differ");
  constexpr int M = Sensor::kMeasDim;
  // dh/dx is zero beyond the first C columns, so is dQ outside its top-left C x C block.
  constexpr int C = jacobian_cols<Sensor>();

  SmallCholesky<M> r_factor;
  if (!r_factor.compute(noise)) return NumericalStatus::kNotPositiveDefinite;

  const Matrix<M, C> h = sensor.jacobian(prior.mean).template leftCols<C>();
  const Vector<M> innovation = sensor.residual(z, sensor.predict(prior.mean));
  Matrix<M, C> r_inv_h;  // R^-1 H
  for (int c = 0; c < C; ++c) r_inv_h.col(c) = r_factor.solve(h.col(c));

  out.station_id = station_id;
  out.delta_information.setZero();
  Covariance<C> block = h.transpose().lazyProduct(r_inv_h);
  symmetrize(block);
  out.delta_information.template topLeftCorner<C, C>() = block;
  out.delta_vector.setZero();
  out.delta_vector.template head<C>() =
      r_inv_h.transpose() * (innovation + h * prior.mean.template head<C>());
  if constexpr (kWithTerms) {
    terms->weighted_innovation = innovation.dot(r_factor.solve(innovation));
    terms->log_det_noise = r_factor.log_determinant();
    terms->measurement_dim = M;
  }
  return NumericalStatus::kOk;
}

}  // namespace detail

/// Writes station `station_id`'s increment for measurement z (noise R) against `prior` into
/// `out`. Fails only if R is not positive definite.
template <int N, typename Sensor>
NumericalStatus compute_increment(int station_id, const GaussianState<N>& prior,
                                  const Sensor& sensor, const Vector<Sensor::kMeasDim>& z,
                                  const Covariance<Sensor::kMeasDim>& noise,
                                  InformationIncrement<N>& out) {
  return detail::compute_increment<false>(station_id, prior, sensor, z, noise, out, nullptr);
}

/// The same increment, and the likelihood terms of the same measurement (an IMM's peers need
/// them) from the same factor of R and the same innovation.
template <int N, typename Sensor>
NumericalStatus compute_increment(int station_id, const GaussianState<N>& prior,
                                  const Sensor& sensor, const Vector<Sensor::kMeasDim>& z,
                                  const Covariance<Sensor::kMeasDim>& noise,
                                  InformationIncrement<N>& out, LikelihoodTerms& terms) {
  return detail::compute_increment<true>(station_id, prior, sensor, z, noise, out, &terms);
}

}  // namespace skyfuse
