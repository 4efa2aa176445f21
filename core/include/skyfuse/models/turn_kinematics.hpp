#pragma once
/// \file
/// The coordinated turn in a horizontal plane, shared by every model that turns (the planar and
/// the 3-D CT). With s = sin(omega dt), c = cos(omega dt):
///   x'  = x + (s/omega) vx - ((1-c)/omega) vy      vx' = c vx - s vy
///   y'  = y + ((1-c)/omega) vx + (s/omega) vy      vy' = s vx + c vy       omega' = omega
/// Near omega = 0 the quotients lose digits: 1 - c is computed as 2 sin^2(omega dt / 2), and
/// the d/d omega terms switch to their Taylor series below |omega dt| = 1e-3 (relative error
/// < 1e-7 there).

#include <cmath>

namespace skyfuse {

/// Where a model keeps the turning components of its state.
struct TurnIndices {
  int x, vx, y, vy, turn_rate;
};

namespace detail {
struct TurnTerms {
  double sin, cos, one_minus_cos, sin_over_rate, one_minus_cos_over_rate;
};
inline TurnTerms turn_terms(double w, double dt) {
  if (w == 0.0) return {0.0, 1.0, 0.0, dt, 0.0};
  const double half = std::sin(0.5 * w * dt);
  const double one_minus_cos = 2.0 * half * half;
  const double s = std::sin(w * dt);
  return {s, std::cos(w * dt), one_minus_cos, s / w, one_minus_cos / w};
}
}  // namespace detail

/// Writes the turned components of `x` into `out` (the others are left alone).
template <typename State>
void propagate_turn(const TurnIndices& i, double dt, const State& x, State& out) {
  const detail::TurnTerms t = detail::turn_terms(x(i.turn_rate), dt);
  out(i.x) = x(i.x) + t.sin_over_rate * x(i.vx) - t.one_minus_cos_over_rate * x(i.vy);
  out(i.vx) = t.cos * x(i.vx) - t.sin * x(i.vy);
  out(i.y) = x(i.y) + t.one_minus_cos_over_rate * x(i.vx) + t.sin_over_rate * x(i.vy);
  out(i.vy) = t.sin * x(i.vx) + t.cos * x(i.vy);
  out(i.turn_rate) = x(i.turn_rate);
}

/// Writes the turned rows of dF/dx at `x` into `f` (which should start as the identity).
template <typename State, typename Jacobian>
void turn_jacobian(const TurnIndices& i, double dt, const State& x, Jacobian& f) {
  constexpr double kSeriesTurnAngle = 1e-3;
  const double w = x(i.turn_rate);
  const double vx = x(i.vx);
  const double vy = x(i.vy);
  const detail::TurnTerms t = detail::turn_terms(w, dt);
  f(i.x, i.vx) = t.sin_over_rate;
  f(i.x, i.vy) = -t.one_minus_cos_over_rate;
  f(i.vx, i.vx) = t.cos;
  f(i.vx, i.vy) = -t.sin;
  f(i.y, i.vx) = t.one_minus_cos_over_rate;
  f(i.y, i.vy) = t.sin_over_rate;
  f(i.vy, i.vx) = t.sin;
  f(i.vy, i.vy) = t.cos;
  // x' depends on omega through vx a - vy b and y' through vx b + vy a, with
  // a = (dt c omega - s) / omega^2 and b = (dt s omega - (1 - c)) / omega^2.
  double a = 0.0;
  double b = 0.0;
  if (std::abs(w * dt) < kSeriesTurnAngle) {
    a = -w * dt * dt * dt / 3.0;
    b = dt * dt / 2.0 - w * w * dt * dt * dt * dt / 8.0;
  } else {
    a = (dt * t.cos * w - t.sin) / (w * w);
    b = (dt * t.sin * w - t.one_minus_cos) / (w * w);
  }
  f(i.x, i.turn_rate) = vx * a - vy * b;
  f(i.y, i.turn_rate) = vx * b + vy * a;
  f(i.vx, i.turn_rate) = -dt * (t.sin * vx + t.cos * vy);
  f(i.vy, i.turn_rate) = dt * (t.cos * vx - t.sin * vy);
}

}  // namespace skyfuse
