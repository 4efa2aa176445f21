#include "skyfuse/experiments/paper001/manoeuvring_path.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "skyfuse/random/counter_rng.hpp"

namespace skyfuse::paper001 {
namespace {

double uniform(CounterRng& rng, double low, double high) {
  return low + (high - low) * rng.uniform();
}
// ±U(low, high): the sign drawn first, then the size, each its own statement (C++ leaves the
// order of a product's operands to the compiler).
double signed_uniform(CounterRng& rng, double low, double high) {
  const double sign = rng.uniform() < 0.5 ? -1.0 : 1.0;
  return sign * uniform(rng, low, high);
}

// What drives the truth during one segment of the path.
struct Segment {
  int steps = 0;
  double acceleration = 0.0;      // a, m/s^2
  double turn_rate_change = 0.0;  // omega_dot, rad/s^2
  bool straight = true;
};

int segment_steps(CounterRng& rng, const PathSetup& setup, double low_s, double high_s) {
  return std::max(1,
                  static_cast<int>(std::lround(uniform(rng, low_s, high_s) / setup.time_step_s)));
}

}  // namespace

ManoeuvringPath generate_path(const PathSetup& setup, std::uint64_t seed, std::uint64_t index) {
  if (setup.steps < 1 || !(setup.time_step_s > 0.0)) {
    throw std::invalid_argument("paper 001 path: steps must be >= 1 and the time step > 0");
  }
  CounterRng motion(NoiseKey{seed, index, 0, 0, NoiseStream::kProcess});
  CounterRng sensor(NoiseKey{seed, index, 0, 0, NoiseStream::kMeasurement});
  const double dt = setup.time_step_s;

  ManoeuvringPath path;
  path.has_sudden_deceleration = motion.uniform() < setup.sudden_deceleration_fraction;
  Vector<5> x;  // [x, y, theta, v, omega]
  x << 0.0, 0.0, uniform(motion, 0.0, 2.0 * std::numbers::pi),
      uniform(motion, 0.0, setup.max_initial_speed_mps), 0.0;

  // Segments alternate, straight first (omega_0 = 0). A path with a sudden deceleration brakes
  // at -20 m/s^2 just before its first manoeuvre and then flies that manoeuvre at +-U(2, 3.5).
  bool straight_next = true;
  bool brake_before_manoeuvre = path.has_sudden_deceleration;
  Segment segment;
  int braking_steps = 0;
  auto start_segment = [&] {
    segment = Segment{};
    segment.straight = straight_next;
    straight_next = !straight_next;
    if (!segment.straight) {
      segment.turn_rate_change = signed_uniform(motion, 0.035, 0.175);
      if (brake_before_manoeuvre) {
        brake_before_manoeuvre = false;
        braking_steps = segment_steps(motion, setup, 0.5, 1.0);
        segment.acceleration = signed_uniform(motion, 2.0, 3.5);
      } else {
        segment.acceleration = signed_uniform(motion, 1.0, 5.0);
      }
    }
    segment.steps =
        segment.straight
            ? segment_steps(motion, setup, setup.min_straight_s, setup.max_straight_s)
            : segment_steps(motion, setup, setup.min_manoeuvre_s, setup.max_manoeuvre_s);
    if (segment.straight) x(4) = 0.0;
  };

  for (int k = 0; k < setup.steps; ++k) {
    path.truth.push_back(x);
    // y's noise first, the order every shipped network and figure was made with (GCC evaluates
    // a call's arguments last first; clang would draw x's first).
    const double noise_y = sensor.normal();
    const double noise_x = sensor.normal();
    path.measurements.emplace_back(x(0) + setup.measurement_std_m * noise_x,
                                   x(1) + setup.measurement_std_m * noise_y);
    if (segment.steps == 0 && braking_steps == 0) start_segment();
    double acceleration = segment.acceleration;
    double turn_rate_change = segment.turn_rate_change;
    if (braking_steps > 0) {  // the braking precedes the curve: no turning while it lasts
      acceleration = -20.0;
      turn_rate_change = 0.0;
      --braking_steps;
    } else {
      --segment.steps;
    }
    // Eq 10, in its order: position from the current heading and speed, then the rates.
    x(0) += x(3) * dt * std::cos(x(2));
    x(1) += x(3) * dt * std::sin(x(2));
    x(2) += x(4) * dt;
    x(3) = std::clamp(x(3) + acceleration * dt, 0.0, setup.max_speed_mps);
    x(4) += turn_rate_change * dt;
  }
  return path;
}

}  // namespace skyfuse::paper001
