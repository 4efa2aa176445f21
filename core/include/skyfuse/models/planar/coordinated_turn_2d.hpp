#pragma once
/// \file
/// Coordinated turn with the turn rate in the state: the CT mode of paper 001's IMM, run as an
/// EKF. State x = [x, vx, y, vy, omega], turning as turn_kinematics.hpp says: eq 25 with its two
/// misprints corrected (SEEDS.md: entry (1,2) is s/omega, entry (2,4) is -s); with the printed
/// matrix the model collapses to constant velocity. Q = blkdiag(sigma_Q^2 D, sigma_Q^2 D,
/// sigma_omega^2 dt), D = [[dt^3/3, dt^2/2], [dt^2/2, dt]]; the paper uses one sigma_Q^2 =
/// sigma_omega^2 for both.

#include "skyfuse/core/types.hpp"
#include "skyfuse/models/planar/planar_state.hpp"
#include "skyfuse/models/turn_kinematics.hpp"

namespace skyfuse {

class CoordinatedTurn2D {
 public:
  static constexpr int kDim = 5;
  using State = Vector<kDim>;

  static constexpr int kX = 0;
  static constexpr int kVx = 1;
  static constexpr int kY = 2;
  static constexpr int kVy = 3;
  static constexpr int kTurnRate = 4;
  static constexpr std::array<int, kDim> kCommonIndex = {
      PlanarState::kX, PlanarState::kVx, PlanarState::kY, PlanarState::kVy, PlanarState::kTurnRate};

  CoordinatedTurn2D(double time_step_s, double acceleration_density)
      : CoordinatedTurn2D(time_step_s, acceleration_density, acceleration_density) {}
  CoordinatedTurn2D(double time_step_s, double acceleration_density, double turn_rate_density)
      : dt_(time_step_s) {
    const double dt = time_step_s;
    Matrix<2, 2> d;
    d << dt * dt * dt / 3.0, dt * dt / 2.0, dt * dt / 2.0, dt;
    process_noise_.setZero();
    process_noise_.block<2, 2>(kX, kX) = acceleration_density * d;
    process_noise_.block<2, 2>(kY, kY) = acceleration_density * d;
    process_noise_(kTurnRate, kTurnRate) = turn_rate_density * dt;
  }

  State propagate(const State& x) const {
    State out;
    propagate_turn(kTurn, dt_, x, out);
    return out;
  }

  Covariance<kDim> jacobian(const State& x) const {
    Covariance<kDim> f = Covariance<kDim>::Identity();
    turn_jacobian(kTurn, dt_, x, f);
    return f;
  }

  const Covariance<kDim>& process_noise() const { return process_noise_; }

 private:
  static constexpr TurnIndices kTurn{kX, kVx, kY, kVy, kTurnRate};

  double dt_;
  Covariance<kDim> process_noise_;
};

}  // namespace skyfuse
