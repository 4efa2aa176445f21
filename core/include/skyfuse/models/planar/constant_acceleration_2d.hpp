#pragma once
/// \file
/// Nearly-constant-acceleration motion in the plane: the CA mode of paper 001's IMM.
///
/// State x = [x, vx, ax, y, vy, ay]. Per axis Phi = [[1, dt, dt^2/2], [0, 1, dt], [0, 0, 1]]
/// and the process noise of a white jerk of spectral density sigma_Q^2:
///   Q = sigma_Q^2 blkdiag(C, C),
///   C = [[dt^5/20, dt^4/8, dt^3/6], [dt^4/8, dt^3/3, dt^2/2], [dt^3/6, dt^2/2, dt]].

#include "skyfuse/core/types.hpp"
#include "skyfuse/models/linear_transition.hpp"
#include "skyfuse/models/planar/planar_state.hpp"

namespace skyfuse {

class ConstantAcceleration2D : public LinearTransition<6> {
 public:
  static constexpr int kX = 0;
  static constexpr int kVx = 1;
  static constexpr int kAx = 2;
  static constexpr int kY = 3;
  static constexpr int kVy = 4;
  static constexpr int kAy = 5;
  static constexpr std::array<int, kDim> kCommonIndex = {PlanarState::kX,  PlanarState::kVx,
                                                         PlanarState::kAx, PlanarState::kY,
                                                         PlanarState::kVy, PlanarState::kAy};

  ConstantAcceleration2D(double time_step_s, double jerk_density) {
    const double dt = time_step_s;
    const double dt2 = dt * dt;
    const double dt3 = dt2 * dt;
    Matrix<3, 3> phi;
    phi << 1.0, dt, dt2 / 2.0, 0.0, 1.0, dt, 0.0, 0.0, 1.0;
    Matrix<3, 3> c;
    c << dt3 * dt2 / 20.0, dt2 * dt2 / 8.0, dt3 / 6.0,  //
        dt2 * dt2 / 8.0, dt3 / 3.0, dt2 / 2.0,          //
        dt3 / 6.0, dt2 / 2.0, dt;
    for (const int axis : {kX, kY}) {
      transition_.block<3, 3>(axis, axis) = phi;
      process_noise_.block<3, 3>(axis, axis) = jerk_density * c;
    }
  }
};

}  // namespace skyfuse
