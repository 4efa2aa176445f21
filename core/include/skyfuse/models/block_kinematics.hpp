#pragma once
/// \file
/// F P F^T for a state ordered by derivative, [p; v; a] with kAxes coordinates in each block,
/// and F = A (x) I_kAxes, A = [[1, dt, dt^2/2], [0, 1, dt], [0, 0, 1]]. Written by block rows and
/// columns as F's structure allows: about a fifth of the multiplications of two dense products,
/// and every caller (every peer) rounds it alike. Paper 000's model (kAxes = 3) and paper 002's
/// relative model (kAxes = 3 or 2) both propagate their covariance with it, then add their Q.

#include "skyfuse/core/types.hpp"

namespace skyfuse {

/// F P F^T; not symmetrised (the filter does that).
template <int kAxes>
Covariance<3 * kAxes> propagate_block_kinematics(const Covariance<3 * kAxes>& p, double dt) {
  constexpr int kPosition = 0;
  constexpr int kVelocity = kAxes;
  constexpr int kAcceleration = 2 * kAxes;
  const double half_dt_sq = 0.5 * dt * dt;
  // F P: every block row is a combination of P's block rows.
  Covariance<3 * kAxes> fp;
  fp.template middleRows<kAxes>(kPosition) =
      p.template middleRows<kAxes>(kPosition) + dt * p.template middleRows<kAxes>(kVelocity) +
      half_dt_sq * p.template middleRows<kAxes>(kAcceleration);
  fp.template middleRows<kAxes>(kVelocity) =
      p.template middleRows<kAxes>(kVelocity) + dt * p.template middleRows<kAxes>(kAcceleration);
  fp.template middleRows<kAxes>(kAcceleration) = p.template middleRows<kAxes>(kAcceleration);
  // (F P) F^T: the same combination of block columns.
  Covariance<3 * kAxes> out;
  out.template middleCols<kAxes>(kPosition) =
      fp.template middleCols<kAxes>(kPosition) + dt * fp.template middleCols<kAxes>(kVelocity) +
      half_dt_sq * fp.template middleCols<kAxes>(kAcceleration);
  out.template middleCols<kAxes>(kVelocity) =
      fp.template middleCols<kAxes>(kVelocity) + dt * fp.template middleCols<kAxes>(kAcceleration);
  out.template middleCols<kAxes>(kAcceleration) = fp.template middleCols<kAxes>(kAcceleration);
  return out;
}

}  // namespace skyfuse
