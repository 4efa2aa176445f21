#pragma once
/// \file
/// Nearly-constant-velocity motion in the plane: paper 001's CVKF (eq 1-9, 13).
///
/// State x = [x, vx, y, vy]. Per axis Phi = [[1, dt], [0, 1]] and the process noise of a
/// piecewise-constant white acceleration of variance sigma_Q^2 held over each step:
///   Q = sigma_Q^2 blkdiag(B, B),   B = [[dt^4/4, dt^3/2], [dt^3/2, dt^2]].

#include "skyfuse/core/types.hpp"
#include "skyfuse/models/planar/planar_state.hpp"

namespace skyfuse {

class ConstantVelocity2D {
 public:
  static constexpr int kDim = 4;
  using State = Vector<kDim>;

  static constexpr int kX = 0;
  static constexpr int kVx = 1;
  static constexpr int kY = 2;
  static constexpr int kVy = 3;
  /// Where each component lives in the planar manoeuvre state the IMM mixes in.
  static constexpr std::array<int, kDim> kCommonIndex = {PlanarState::kX, PlanarState::kVx,
                                                         PlanarState::kY, PlanarState::kVy};

  ConstantVelocity2D(double time_step_s, double acceleration_variance) {
    const double dt = time_step_s;
    transition_.setIdentity();
    transition_(kX, kVx) = dt;
    transition_(kY, kVy) = dt;
    Matrix<2, 2> b;
    b << dt * dt * dt * dt / 4.0, dt * dt * dt / 2.0, dt * dt * dt / 2.0, dt * dt;
    process_noise_.setZero();
    process_noise_.block<2, 2>(kX, kX) = acceleration_variance * b;
    process_noise_.block<2, 2>(kY, kY) = acceleration_variance * b;
  }

  State propagate(const State& x) const { return transition_ * x; }
  /// The model is linear: dF/dx is F wherever it is evaluated.
  const Covariance<kDim>& jacobian(const State& /*x*/) const { return transition_; }
  const Covariance<kDim>& process_noise() const { return process_noise_; }

 private:
  Covariance<kDim> transition_;
  Covariance<kDim> process_noise_;
};

}  // namespace skyfuse
