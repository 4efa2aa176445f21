#pragma once
/// \file
/// Coordinated turn with the turn rate in the state: the CT mode of paper 001's IMM, run as an
/// EKF. State x = [x, vx, y, vy, omega]. With s = sin(omega dt), c = cos(omega dt):
///   x'  = x + (s/omega) vx - ((1-c)/omega) vy      vx' = c vx - s vy
///   y'  = y + ((1-c)/omega) vx + (s/omega) vy      vy' = s vx + c vy       omega' = omega
/// This is eq 25 with its two misprints corrected (SEEDS.md: entry (1,2) is s/omega, entry (2,4)
/// is -s); with the printed matrix the model collapses to constant velocity.
/// Q = blkdiag(sigma_Q^2 D, sigma_Q^2 D, sigma_omega^2 dt), D = [[dt^3/3, dt^2/2], [dt^2/2, dt]];
/// the paper uses one sigma_Q^2 = sigma_omega^2 for both.
///
/// Near omega = 0 the quotients lose digits: 1 - c is computed as 2 sin^2(omega dt / 2), and
/// the d/d omega terms switch to their Taylor series below |omega dt| = 1e-3.

#include <cmath>

#include "skyfuse/core/types.hpp"
#include "skyfuse/models/planar/planar_state.hpp"

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
  /// Below this |omega dt| the d/d omega terms use their series (relative error < 1e-7 there).
  static constexpr double kSeriesTurnAngle = 1e-3;

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
    const Turn t = turn(x(kTurnRate));
    State out;
    out(kX) = x(kX) + t.sin_over_rate * x(kVx) - t.one_minus_cos_over_rate * x(kVy);
    out(kVx) = t.cos * x(kVx) - t.sin * x(kVy);
    out(kY) = x(kY) + t.one_minus_cos_over_rate * x(kVx) + t.sin_over_rate * x(kVy);
    out(kVy) = t.sin * x(kVx) + t.cos * x(kVy);
    out(kTurnRate) = x(kTurnRate);
    return out;
  }

  Covariance<kDim> jacobian(const State& x) const {
    const double w = x(kTurnRate);
    const double vx = x(kVx);
    const double vy = x(kVy);
    const Turn t = turn(w);
    Covariance<kDim> f = Covariance<kDim>::Identity();
    f(kX, kVx) = t.sin_over_rate;
    f(kX, kVy) = -t.one_minus_cos_over_rate;
    f(kVx, kVx) = t.cos;
    f(kVx, kVy) = -t.sin;
    f(kY, kVx) = t.one_minus_cos_over_rate;
    f(kY, kVy) = t.sin_over_rate;
    f(kVy, kVx) = t.sin;
    f(kVy, kVy) = t.cos;
    // x' depends on omega through vx a - vy b and y' through vx b + vy a, with
    // a = (dt c omega - s) / omega^2 and b = (dt s omega - 1 + c) / omega^2.
    double a = 0.0;
    double b = 0.0;
    if (std::abs(w * dt_) < kSeriesTurnAngle) {
      a = -w * dt_ * dt_ * dt_ / 3.0;
      b = dt_ * dt_ / 2.0 - w * w * dt_ * dt_ * dt_ * dt_ / 8.0;
    } else {
      const double w2 = w * w;
      a = (dt_ * t.cos * w - t.sin) / w2;
      b = (dt_ * t.sin * w - t.one_minus_cos) / w2;
    }
    f(kX, kTurnRate) = vx * a - vy * b;
    f(kY, kTurnRate) = vx * b + vy * a;
    f(kVx, kTurnRate) = -dt_ * (t.sin * vx + t.cos * vy);
    f(kVy, kTurnRate) = dt_ * (t.cos * vx - t.sin * vy);
    return f;
  }

  const Covariance<kDim>& process_noise() const { return process_noise_; }

 private:
  struct Turn {
    double sin, cos, one_minus_cos, sin_over_rate, one_minus_cos_over_rate;
  };
  Turn turn(double w) const {
    const double s = std::sin(w * dt_);
    const double half = std::sin(0.5 * w * dt_);
    const double one_minus_cos = 2.0 * half * half;
    if (w == 0.0) return {0.0, 1.0, 0.0, dt_, 0.0};
    return {s, std::cos(w * dt_), one_minus_cos, s / w, one_minus_cos / w};
  }

  double dt_;
  Covariance<kDim> process_noise_;
};

}  // namespace skyfuse
