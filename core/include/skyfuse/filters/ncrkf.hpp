#pragma once
/// \file
/// Paper 002's noise-correlation robust Kalman filter (NCRKF, Eq 10-11 as corrected in
/// SEEDS.md) and the two linear filters it is compared with, all one update in information form
/// over pseudo-linear TDOA rows (models/tdoa/pseudo_linear_tdoa.hpp):
///
///   Y+ = Y- + sum_j (H_j^T R_j^-1 H_j - W_j),   Y+ x+ = Y- x- + sum_j (H_j^T R_j^-1 y_j - V_j).
///
/// Eq 11, x+ = (I + P+ W) x- + P+ H^T R^-1 (y - H x-) - P+ V, is the same update (multiply it
/// by Y+). Each receiver's term is an information increment (fusion/increment_fusion.hpp), so
/// the NCRKF decentralises like any EKF of paper 000: each receiver publishes its own.
///
///  - kCompensated: the NCRKF, rows built with r~ (W, V subtracted);
///  - kNone with rows built with r~: the nominal KF (recursive pseudo-linear least squares),
///    biased;
///  - kNone with rows built with the true r: the optimal KF, a bound no real filter reaches.
///
/// One receiver's H~^T R^-1 H~ - W need not be positive semi-definite; Y+ must be positive
/// definite, which the Cholesky factorisation of the fusion checks: if it is not, the update
/// reports kNotPositiveDefinite and leaves the state as it was.

#include <span>
#include <vector>

#include "skyfuse/fusion/increment_fusion.hpp"
#include "skyfuse/fusion/information_increment.hpp"
#include "skyfuse/models/tdoa/pseudo_linear_tdoa.hpp"

namespace skyfuse {

enum class BiasCompensation { kNone, kCompensated };

/// Receiver `station_id`'s information increment for `row`.
inline InformationIncrement<PseudoLinearTdoaRow::kDim> tdoa_increment(
    int station_id, const PseudoLinearTdoaRow& row, BiasCompensation compensation) {
  constexpr int kRange = PseudoLinearTdoaRow::kRange;
  InformationIncrement<PseudoLinearTdoaRow::kDim> out;
  out.station_id = station_id;
  out.delta_information.noalias() = row.h.transpose() * row.h / row.noise;
  out.delta_vector = row.h.transpose() * (row.y / row.noise);
  if (compensation == BiasCompensation::kCompensated) {
    out.delta_information(kRange, kRange) -= row.w;
    out.delta_vector(kRange) -= row.v;
  }
  return out;
}

/// What tdoa_update() keeps between calls, so that a step allocates nothing once it has grown.
struct TdoaUpdateScratch {
  std::vector<InformationIncrement<PseudoLinearTdoaRow::kDim>> increments;
  std::vector<double> weights;
};

/// The update of `state` with every receiver's row (weights 1, in the rows' order).
inline NumericalStatus tdoa_update(GaussianState<PseudoLinearTdoaRow::kDim>& state,
                                   std::span<const PseudoLinearTdoaRow> rows,
                                   BiasCompensation compensation, TdoaUpdateScratch& scratch) {
  scratch.increments.clear();
  for (std::size_t j = 0; j < rows.size(); ++j) {
    scratch.increments.push_back(tdoa_increment(static_cast<int>(j) + 1, rows[j], compensation));
  }
  scratch.weights.assign(rows.size(), 1.0);
  return fuse_increments(
      state, std::span<const InformationIncrement<PseudoLinearTdoaRow::kDim>>(scratch.increments),
      scratch.weights, state);
}

}  // namespace skyfuse
