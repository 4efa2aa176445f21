#pragma once
/// \file
/// Paper 002's TDOA measurement in pseudo-linear form (Eq 3-6, corrected in SEEDS.md), for the
/// relative state x = [dx, dy, d_t1, ...] (dx, dy: target minus the reference UAV 1; d_t1 the
/// target's range to UAV 1; BlockConstantAcceleration<3>).
///
/// Receiver j measures the range difference r_j = |p_t - p_j| - |p_t - p_1| with white noise,
/// r~_j = r_j + dr_j, dr_j ~ (0, sigma^2). With P_j = p_j - p_1 (known from navigation) and
/// d_j1 = |P_j|, squaring gives the exact linear identity (Eq 3)
///
///   r_j^2 - d_j1^2 = -2 [P_jx, P_jy, r_j] [dx, dy, d_t1]^T,
///
/// so y_j = r~_j^2 - d_j1^2 - sigma^2 = H_j x + v_j with H_j = -2 [P_jx, P_jy, r_j, 0...] and
/// v_j = 2 r_j dr_j + dr_j^2 - sigma^2 (zero mean, variance R_j = 2 sigma^2 (2 r_j^2 + sigma^2)).
/// A filter knows only H~_j = -2 [P_jx, P_jy, r~_j, 0...]: its third entry carries the same
/// dr_j as v_j, so E[H~^T R^-1 (y - H~ x)] = V - W x with
///
///   W_j = e3 e3^T 2 / (2 r_j^2 + sigma^2),   V_j = -e3 2 r_j / (2 r_j^2 + sigma^2)
///
/// (the paper's V lacks r_j in the numerator). That is the nominal filter's bias; the NCRKF
/// subtracts it (filters/ncrkf.hpp).

#include <cmath>

#include "skyfuse/core/types.hpp"

namespace skyfuse {

/// One receiver's row of the pseudo-linear measurement and its statistics.
struct PseudoLinearTdoaRow {
  static constexpr int kDim = 9;
  static constexpr int kRange = 2;  ///< index of d_t1, where H's noisy entry and W, V sit
  Eigen::Matrix<double, 1, kDim> h = Eigen::Matrix<double, 1, kDim>::Zero();
  double y = 0.0;
  double noise = 0.0;  ///< R_j
  double w = 0.0;      ///< W_j's only non-zero entry, (3, 3)
  double v = 0.0;      ///< V_j's only non-zero entry, the third
};

/// Receiver j's row: `offset` = P_j = p_j - p_1, `measured` = r~_j, `model_range` = the range
/// difference H, R, W and V are evaluated at (r~_j for the NCRKF and the nominal filter; the
/// true r_j for the optimal filter, which no real filter knows), `sigma` the noise's standard
/// deviation.
inline PseudoLinearTdoaRow pseudo_linear_tdoa_row(const Vector<2>& offset, double measured,
                                                  double model_range, double sigma) {
  const double sigma2 = sigma * sigma;
  const double spread = 2.0 * model_range * model_range + sigma2;
  PseudoLinearTdoaRow row;
  row.h(0) = -2.0 * offset.x();
  row.h(1) = -2.0 * offset.y();
  row.h(PseudoLinearTdoaRow::kRange) = -2.0 * model_range;
  row.y = measured * measured - offset.squaredNorm() - sigma2;
  row.noise = 2.0 * sigma2 * spread;
  row.w = 2.0 / spread;
  row.v = -2.0 * model_range / spread;
  return row;
}

/// The true range difference of a target at `relative` = p_t - p_1 for a receiver at `offset`.
inline double range_difference(const Vector<2>& relative, const Vector<2>& offset) {
  return (relative - offset).norm() - relative.norm();
}

}  // namespace skyfuse
