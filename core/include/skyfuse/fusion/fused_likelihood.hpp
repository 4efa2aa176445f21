#pragma once
/// \file
/// The likelihood of a round's stacked measurement, formed by every peer from the stations'
/// increments and two scalars each, so that a network of peers weighs the modes of an IMM
/// exactly as a central IMM on the stacked measurement does.
///
/// For the stacked z = [z_1; ...; z_M], H, R = blkdiag(R_i) and a prior N(x-, P-):
///   S = H P- H^T + R,   log N(nu; 0, S) = -(nu^T S^-1 nu + log det S + m log 2 pi) / 2.
/// With dQ = sum_i dQ_i = H^T R^-1 H, b = H^T R^-1 nu = dy - dQ x- (dy = sum_i dy_i), and the
/// fused Y+ = (P-)^-1 + dQ, x+ = (Y+)^-1 ((P-)^-1 x- + dy), so that b = Y+ (x+ - x-):
///   nu^T S^-1 nu = sum_i nu_i^T R_i^-1 nu_i - b^T (Y+)^-1 b        (Woodbury)
///                = sum_i nu_i^T R_i^-1 nu_i - (x+ - x-)^T Y+ (x+ - x-)
///   det S = det R det(I + P- dQ) = prod_i det R_i  det Y+ det P-    (determinant lemma)
/// so each station adds to its increment nu_i^T R_i^-1 nu_i and log det R_i (LikelihoodTerms,
/// which compute_increment fills from its own factor of R_i).
/// A station weighted by w_i counts as one with noise R_i / w_i, as in the fusion itself.

#include <cmath>
#include <span>

#include "skyfuse/core/small_cholesky.hpp"
#include "skyfuse/filters/kalman.hpp"
#include "skyfuse/fusion/increment_fusion.hpp"
#include "skyfuse/fusion/information_increment.hpp"

namespace skyfuse {

/// Adds station terms `t` of fusion weight `w` to `sum`: a station weighted by w counts as one
/// with noise R / w (nu^T (R/w)^-1 nu = w nu^T R^-1 nu, log det (R/w) = log det R - m log w).
/// Sums of terms add, so a tree exchange's cluster sums them too (fusion/partial_sum.hpp).
inline void add_weighted_terms(LikelihoodTerms& sum, const LikelihoodTerms& t, double w) {
  sum.weighted_innovation += w * t.weighted_innovation;
  sum.log_det_noise += t.log_det_noise - t.measurement_dim * std::log(w);
  sum.measurement_dim += t.measurement_dim;
}

/// Adds a later cluster's summed terms to `sum` (their weights are inside already).
inline void add_terms(LikelihoodTerms& sum, const LikelihoodTerms& later) {
  sum.weighted_innovation += later.weighted_innovation;
  sum.log_det_noise += later.log_det_noise;
  sum.measurement_dim += later.measurement_dim;
}

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

  LikelihoodTerms sum;
  for (std::size_t i = 0; i < increments.size(); ++i) add_weighted_terms(sum, terms[i], weights[i]);
  measurement_dim = sum.measurement_dim;
  // fuse_increments factorised P- and Y+ already, inside; these two factorisations repeat that
  // work for the determinants (the IMM's path only, not the single-model one).
  SmallCholesky<N> prior_factor;
  SmallCholesky<N> fused_factor;
  prior_factor.compute(prior.covariance);
  fused_factor.compute(information);
  const Vector<N> step = fused.mean - prior.mean;

  UpdateReport report;
  report.nis = sum.weighted_innovation - step.dot(information * step);
  report.log_det_innovation =
      sum.log_det_noise + fused_factor.log_determinant() + prior_factor.log_determinant();
  posterior = fused;
  return report;
}

}  // namespace skyfuse
