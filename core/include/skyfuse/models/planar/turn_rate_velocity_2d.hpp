#pragma once
/// \file
/// Constant turn rate and velocity (CTRV) in polar form: paper 001's EKF (eq 15-17).
/// State x = [x, y, theta, v, omega]; one Euler step of the kinematics:
///   x' = x + v dt cos(theta),  y' = y + v dt sin(theta),  theta' = theta + omega dt,
///   v' = v,  omega' = omega.
///
/// The paper's process noise (kPrinted) is sigma_Q^2 times diag(dt^4/4, dt^4/4, dt^4/4, dt^2,
/// dt^2) with Q14 = Q24 = Q35 = dt^3/2. It is indefinite: its {x, y, v} block has determinant
/// a (a c - 2 b^2) < 0 (a = dt^4/4, b = dt^3/2, c = dt^2); at dt = 0.1 and
/// sigma_Q^2 = 10 its smallest eigenvalue is -2.5e-4. kPositiveSemidefinite (the default) instead
/// drives the state with the two accelerations the model leaves out, a white tangential
/// acceleration and a white angular acceleration, each of variance sigma_Q^2:
///   Q = sigma_Q^2 (g_a g_a^T + g_alpha g_alpha^T),
///   g_a = [dt^2/2 cos(theta), dt^2/2 sin(theta), 0, dt, 0],  g_alpha = [0, 0, dt^2/2, 0, dt].

#include <cmath>

#include "skyfuse/core/types.hpp"

namespace skyfuse {

enum class TurnRateNoise { kPositiveSemidefinite, kPrinted };

class TurnRateVelocity2D {
 public:
  static constexpr int kDim = 5;
  using State = Vector<kDim>;

  static constexpr int kX = 0;
  static constexpr int kY = 1;
  static constexpr int kHeading = 2;
  static constexpr int kSpeed = 3;
  static constexpr int kTurnRate = 4;

  TurnRateVelocity2D(double time_step_s, double acceleration_variance,
                     TurnRateNoise noise = TurnRateNoise::kPositiveSemidefinite)
      : dt_(time_step_s), variance_(acceleration_variance), noise_(noise) {
    const double dt = time_step_s;
    const double a = dt * dt * dt * dt / 4.0;
    const double b = dt * dt * dt / 2.0;
    const double c = dt * dt;
    printed_noise_ = Vector<kDim>(a, a, a, c, c).asDiagonal();
    for (const auto& [row, col] : {std::pair{kX, kSpeed}, {kY, kSpeed}, {kHeading, kTurnRate}}) {
      printed_noise_(row, col) = b;
      printed_noise_(col, row) = b;
    }
    printed_noise_ *= acceleration_variance;
  }

  State propagate(const State& x) const {
    State out = x;
    out(kX) += x(kSpeed) * dt_ * std::cos(x(kHeading));
    out(kY) += x(kSpeed) * dt_ * std::sin(x(kHeading));
    out(kHeading) += x(kTurnRate) * dt_;
    return out;
  }

  Covariance<kDim> jacobian(const State& x) const {
    const double s = std::sin(x(kHeading));
    const double c = std::cos(x(kHeading));
    Covariance<kDim> f = Covariance<kDim>::Identity();
    f(kX, kHeading) = -x(kSpeed) * dt_ * s;
    f(kX, kSpeed) = dt_ * c;
    f(kY, kHeading) = x(kSpeed) * dt_ * c;
    f(kY, kSpeed) = dt_ * s;
    f(kHeading, kTurnRate) = dt_;
    return f;
  }

  /// Q at the prior mean x (the positive semi-definite form depends on the heading).
  Covariance<kDim> process_noise(const State& x) const {
    if (noise_ == TurnRateNoise::kPrinted) return printed_noise_;
    const double half_dt2 = dt_ * dt_ / 2.0;
    Vector<kDim> g_a(half_dt2 * std::cos(x(kHeading)), half_dt2 * std::sin(x(kHeading)), 0.0, dt_,
                     0.0);
    Vector<kDim> g_alpha(0.0, 0.0, half_dt2, 0.0, dt_);
    return variance_ * (g_a * g_a.transpose() + g_alpha * g_alpha.transpose());
  }

 private:
  double dt_;
  double variance_;
  TurnRateNoise noise_;
  Covariance<kDim> printed_noise_;
};

}  // namespace skyfuse
