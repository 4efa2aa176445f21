#pragma once
/// \file
/// Nearly-constant-velocity motion in the plane: paper 001's CVKF (eq 1-9, 13).
///
/// State x = [x, vx, y, vy]. Per axis Phi = [[1, dt], [0, 1]] and the process noise of a
/// piecewise-constant white acceleration of variance sigma_Q^2 held over each step:
///   Q = sigma_Q^2 blkdiag(B, B),   B = [[dt^4/4, dt^3/2], [dt^3/2, dt^2]].

#include "skyfuse/core/types.hpp"
#include "skyfuse/models/linear_transition.hpp"
#include "skyfuse/models/planar/planar_state.hpp"

namespace skyfuse {

class ConstantVelocity2D : public LinearTransition<4> {
 public:
  static constexpr int kX = 0;
  static constexpr int kVx = 1;
  static constexpr int kY = 2;
  static constexpr int kVy = 3;
  /// Where each component lives in the planar manoeuvre state the IMM mixes in.
  static constexpr std::array<int, kDim> kCommonIndex = {PlanarState::kX, PlanarState::kVx,
                                                         PlanarState::kY, PlanarState::kVy};

  ConstantVelocity2D(double time_step_s, double acceleration_variance) {
    const double dt = time_step_s;
    transition_(kX, kVx) = dt;
    transition_(kY, kVy) = dt;
    Matrix<2, 2> b;
    b << dt * dt * dt * dt / 4.0, dt * dt * dt / 2.0, dt * dt * dt / 2.0, dt * dt;
    process_noise_.block<2, 2>(kX, kX) = acceleration_variance * b;
    process_noise_.block<2, 2>(kY, kY) = acceleration_variance * b;
  }
};

}  // namespace skyfuse
