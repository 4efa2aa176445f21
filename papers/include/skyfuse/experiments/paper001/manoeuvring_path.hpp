#pragma once
/// \file
/// Paper 001's synthetic manoeuvring paths (§III, eq 10-11) with the defaults SEEDS.md fixes
/// where the paper is silent. Truth x = [x, y, theta, v, omega], integrated with dt = 0.1 s:
///   x += v dt cos(theta);  y += v dt sin(theta);  theta += omega dt;  v += a dt;
///   omega += omega_dot dt.
/// A path alternates straight segments (a = omega_dot = 0, omega reset to 0), lasting U(1,4) s,
/// and manoeuvre segments (a = +-U(1,5) m/s^2, omega_dot = +-U(0.035,0.175) rad/s^2), lasting
/// U(2,6) s.
/// In a tenth of the paths a manoeuvre is entered by a sudden deceleration of -20 m/s^2 for
/// U(0.5,1) s and then flown with a = +-U(2,3.5) m/s^2. Speed stays in [0, 40] m/s.
/// The sensor reports x and y, each with N(0, 3^2) noise (eq 11).

#include <cmath>
#include <cstdint>
#include <vector>

#include "skyfuse/core/types.hpp"

namespace skyfuse::paper001 {

struct PathSetup {
  double time_step_s = 0.1;
  /// L and the straight segments' length are not given by the paper. These values make the
  /// generated set's Table 1 match the paper's: the training windows' CVKF error has a standard
  /// deviation of 2.81 m per axis (paper 2.84 / 2.86) and their true position one of about
  /// 213 m (paper 210.66 / 213.75); SEEDS.md's first guess, L = 300 with U(2,6) s straights,
  /// gave 2.48 m and 194 m.
  int steps = 340;
  double measurement_std_m = 3.0;
  double max_initial_speed_mps = 30.0;  ///< v0 ~ U(0, 30)
  double max_speed_mps = 40.0;
  double min_manoeuvre_s = 2.0;
  double max_manoeuvre_s = 6.0;
  double min_straight_s = 1.0;
  double max_straight_s = 4.0;
  double sudden_deceleration_fraction = 0.1;
};

struct ManoeuvringPath {
  /// Truth at steps 0..L-1: [x, y, theta, v, omega].
  std::vector<Vector<5>> truth;
  /// The sensor's [x, y] at each step.
  std::vector<Vector<2>> measurements;
  bool has_sudden_deceleration = false;
};

/// A truth [x, y, theta, v, omega] as the Cartesian [x, vx, y, vy] the planar models start from.
inline Vector<4> cartesian_position_velocity(const Vector<5>& truth) {
  return {truth(0), truth(3) * std::cos(truth(2)), truth(1), truth(3) * std::sin(truth(2))};
}

/// Path `index` of the set drawn with `seed`: a pure function of (setup, seed, index).
ManoeuvringPath generate_path(const PathSetup& setup, std::uint64_t seed, std::uint64_t index);

}  // namespace skyfuse::paper001
