#pragma once
/// \file
/// The likelihood of a round's stacked measurement, formed by every peer from the stations'
/// increments and two scalars each, so that a network of peers weighs the modes of an IMM
/// exactly as a central IMM on the stacked measurement does.
///
/// For the stacked z = [z_1; ...; z_M], H, R = blkdiag(R_i) and a prior N(x-, P-):
///   S = H P- H^T + R,   log N(nu; 0, S) = -(nu^T S^-1 nu + log det S + m log 2 pi) / 2.
/// With dQ = sum_i dQ_i = H^T R^-1 H, b = H^T R^-1 nu = dy - dQ x- (dy = sum_i dy_i), and the
/// fused Y+ = (P-)^-1 + dQ, x+ = (Y+)^-1 ((P-)^-1 x- + dy):
///   nu^T S^-1 nu = sum_i nu_i^T R_i^-1 nu_i - b^T (Y+)^-1 b        (Woodbury)
///                = sum_i nu_i^T R_i^-1 nu_i - b^T (x+ - x-)
///   det S = det R det(I + P- dQ) = prod_i det R_i  det Y+ det P-    (determinant lemma)
/// so each station adds to its increment nu_i^T R_i^-1 nu_i and log det R_i (LikelihoodTerms).
/// A station weighted by w_i counts as one with noise R_i / w_i, as in the fusion itself.

#include <Eigen/Cholesky>
#include <cmath>
#include <span>

#include "skyfuse/core/llt_success.hpp"
#include "skyfuse/filters/kalman.hpp"
#include "skyfuse/fusion/increment_fusion.hpp"
#include "skyfuse/fusion/information_increment.hpp"

namespace skyfuse {

/// What a station sends beside its increment for the likelihood; all zero for a station whose
/// measurement was screened out (it adds nothing, like its zero increment).
struct LikelihoodTerms {
  double weighted_innovation = 0.0;  ///< nu_i^T R_i^-1 nu_i
  double log_det_noise = 0.0;        ///< log det R_i
  int measurement_dim = 0;           ///< m_i
};

/// compute_increment() and the station's likelihood terms for the same measurement.
template <int N, typename Sensor>
NumericalStatus compute_increment_with_likelihood(int station_id, const GaussianState<N>& prior,
                                                  const Sensor& sensor,
                                                  const Vector<Sensor::kMeasDim>& z,
                                                  const Covariance<Sensor::kMeasDim>& noise,
                                                  InformationIncrement<N>& out,
                                                  LikelihoodTerms& terms) {
  const NumericalStatus status = compute_increment(station_id, prior, sensor, z, noise, out);
  if (status != NumericalStatus::kOk) return status;
  const Eigen::LLT<Covariance<Sensor::kMeasDim>> r_factor(noise);
  const Vector<Sensor::kMeasDim> innovation = sensor.residual(z, sensor.predict(prior.mean));
  terms.weighted_innovation = innovation.dot(r_factor.solve(innovation));
  terms.log_det_noise = 2.0 * r_factor.matrixLLT().diagonal().array().log().sum();
  terms.measurement_dim = Sensor::kMeasDim;
  return NumericalStatus::kOk;
}

namespace detail {
template <int N>
double log_det_spd(const Covariance<N>& a) {
  const Eigen::LLT<Covariance<N>> factor(a);
  return 2.0 * factor.matrixLLT().diagonal().array().log().sum();
}
}  // namespace detail

/// fuse_increments() onto `prior`, and the log-likelihood of the stacked measurement the
/// increments stand for: the report's nis is nu^T S^-1 nu, its log_det_innovation log det S,
/// and log_likelihood(measurement_dim) with the returned dimension gives log N(nu; 0, S).
/// `terms[i]` belongs to `increments[i]`. On failure `posterior` is left unchanged.
template <int N, typename Increments, typename Terms>
UpdateReport fuse_increments_with_likelihood(const GaussianState<N>& prior,
                                             const Increments& increments, const Terms& terms,
                                             std::span<const double> weights,
                                             GaussianState<N>& posterior, int& measurement_dim) {
  GaussianState<N> fused;
  Covariance<N> information;
  const NumericalStatus status = fuse_increments(prior, increments, weights, fused, &information);
  if (status != NumericalStatus::kOk) return {status};

  Covariance<N> delta_information = Covariance<N>::Zero();
  Vector<N> delta_vector = Vector<N>::Zero();
  double weighted_innovation = 0.0;
  double log_det_noise = 0.0;
  measurement_dim = 0;
  for (std::size_t i = 0; i < increments.size(); ++i) {
    const double w = weights[i];
    delta_information += w * increments[i].delta_information;
    delta_vector += w * increments[i].delta_vector;
    const LikelihoodTerms& t = terms[i];
    weighted_innovation += w * t.weighted_innovation;
    log_det_noise += t.log_det_noise - t.measurement_dim * std::log(w);
    measurement_dim += t.measurement_dim;
  }
  const Vector<N> b = delta_vector - delta_information * prior.mean;

  UpdateReport report;
  report.nis = weighted_innovation - b.dot(fused.mean - prior.mean);
  report.log_det_innovation = log_det_noise + detail::log_det_spd<N>(information) +
                              detail::log_det_spd<N>(prior.covariance);
  posterior = fused;
  return report;
}

}  // namespace skyfuse
