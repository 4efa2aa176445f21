#pragma once
/// \file
/// Angle wrapping. The convention everywhere is the half-open interval (-pi, pi].

#include <cmath>
#include <numbers>

namespace skyfuse {

/// Wraps an angle in radians into (-pi, pi]. Both -pi and pi map to pi, so a difference of
/// two bearings on either side of the cut is always the short way round.
inline double wrap_angle(double radians) {
  constexpr double kPi = std::numbers::pi;
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  // Nearly every angle met (a bearing, a difference of two) is already in range: return it
  // as is, bit for bit what remainder() would give, without the call.
  if (radians > -kPi && radians <= kPi) return radians;
  // remainder() is exact and returns a value in [-pi, pi]; only -pi needs moving.
  double wrapped = std::remainder(radians, kTwoPi);
  if (wrapped <= -kPi) wrapped += kTwoPi;
  return wrapped;
}

}  // namespace skyfuse
