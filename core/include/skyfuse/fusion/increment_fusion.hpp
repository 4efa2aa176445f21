#pragma once
/// \file
/// Weighted fusion of information increments into a common prior (paper 000, Sec. III):
///
///   Y = (P^-)^-1 + sum_i w_i dQ_i,   y = (P^-)^-1 x^- + sum_i w_i dy_i,   P = Y^-1,  x = P y.
///
/// The sums run in ascending station id and every inverse goes through a Cholesky factor, so any
/// two peers holding the same prior and the same increments compute the same bits.

#include <cassert>
#include <span>

#include "skyfuse/core/small_cholesky.hpp"
#include "skyfuse/core/status.hpp"
#include "skyfuse/core/types.hpp"
#include "skyfuse/fusion/information_increment.hpp"

namespace skyfuse {

/// Fuses `increments` (ascending station id; weights[i] belongs to increments[i]) into `prior`
/// and writes the result to `posterior`, which may alias `prior`. On failure `posterior` is
/// left unchanged. If `fused_information` is given it receives Y = P^-1 of the posterior, which
/// the fusion computes anyway (NEES = e^T Y e needs no further factorisation).
/// `Increments` is any random-access range of InformationIncrement<N> (a span, an
/// IndirectView).
template <int N, typename Increments>
NumericalStatus fuse_increments(const GaussianState<N>& prior, const Increments& increments,
                                std::span<const double> weights, GaussianState<N>& posterior,
                                Covariance<N>* fused_information = nullptr) {
  assert(weights.size() == increments.size() && "one weight per increment");
  for (std::size_t i = 1; i < increments.size(); ++i) {
    if (increments[i].station_id <= increments[i - 1].station_id) {
      return NumericalStatus::kIncrementsOutOfOrder;
    }
  }

  SmallCholesky<N> prior_factor;
  if (!prior_factor.compute(prior.covariance)) return NumericalStatus::kNotPositiveDefinite;

  // y- = Y- x- and, below, x = P y: the paper's own formulas, and matrix-vector products with
  // matrices already at hand, cheaper than two more triangular solves.
  Covariance<N> information = prior_factor.inverse();
  Vector<N> information_vector = information * prior.mean;
  for (std::size_t i = 0; i < increments.size(); ++i) {
    const InformationIncrement<N>& increment = increments[i];
    information.noalias() += weights[i] * increment.delta_information;
    information_vector.noalias() += weights[i] * increment.delta_vector;
  }

  SmallCholesky<N> fused_factor;
  if (!fused_factor.compute(information)) return NumericalStatus::kNotPositiveDefinite;
  if (fused_information != nullptr) *fused_information = information;
  posterior.covariance = fused_factor.inverse();
  posterior.mean = posterior.covariance * information_vector;
  return NumericalStatus::kOk;
}

}  // namespace skyfuse
