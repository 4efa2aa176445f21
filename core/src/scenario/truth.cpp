#include "skyfuse/scenario/truth.hpp"

#include <cmath>

namespace skyfuse {
namespace {

struct Kinematics {
  Vector3 position;
  Vector3 velocity;
};

// Which manoeuvre, if any, acts over the step [k, k+1). Later entries win on overlap; the
// loader refuses overlaps, so this is only a tie-break for scenarios built in code.
const Manoeuvre* active_manoeuvre(const std::vector<Manoeuvre>& manoeuvres, int step, double dt) {
  const Manoeuvre* active = nullptr;
  for (const Manoeuvre& m : manoeuvres) {
    const long first = std::lround(m.start_s / dt);
    const long end = std::lround((m.start_s + m.duration_s) / dt);
    if (step >= first && step < end) active = &m;
  }
  return active;
}

// Exact circular arc in the horizontal plane; vertical motion continues unchanged.
Vector3 advance_turn(Kinematics& k, double rate, double dt) {
  const double angle = rate * dt;
  const double s = std::sin(angle);
  const double c = std::cos(angle);
  const double vx = k.velocity.x();
  const double vy = k.velocity.y();
  const Vector3 acceleration(-rate * vy, rate * vx, 0.0);
  k.position.x() += (vx * s - vy * (1.0 - c)) / rate;
  k.position.y() += (vy * s + vx * (1.0 - c)) / rate;
  k.position.z() += k.velocity.z() * dt;
  k.velocity.x() = vx * c - vy * s;
  k.velocity.y() = vx * s + vy * c;
  return acceleration;
}

Vector3 advance_constant_acceleration(Kinematics& k, const Vector3& acceleration, double dt) {
  k.position += k.velocity * dt + 0.5 * dt * dt * acceleration;
  k.velocity += acceleration * dt;
  return acceleration;
}

}  // namespace

TruthTrajectory generate_truth(const TargetConfig& target, double speed_mps, double time_step_s,
                               int steps) {
  TruthTrajectory truth;
  truth.states.resize(static_cast<std::size_t>(steps) + 1);
  Kinematics k{target.initial_position_m, target.direction.normalized() * speed_mps};

  for (int step = 0; step <= steps; ++step) {
    const Vector3 position = k.position;
    const Vector3 velocity = k.velocity;
    Vector3 acceleration = Vector3::Zero();
    const Manoeuvre* m = active_manoeuvre(target.manoeuvres, step, time_step_s);
    if (m != nullptr && m->kind == Manoeuvre::Kind::kTurn && m->turn_rate_rad_s != 0.0) {
      acceleration = advance_turn(k, m->turn_rate_rad_s, time_step_s);
    } else {
      const Vector3 a = (m != nullptr && m->kind == Manoeuvre::Kind::kAccelerate)
                            ? m->acceleration_mps2
                            : Vector3::Zero();
      acceleration = advance_constant_acceleration(k, a, time_step_s);
    }
    auto& state = truth.states[static_cast<std::size_t>(step)];
    state << position, velocity, acceleration;
  }
  return truth;
}

}  // namespace skyfuse
