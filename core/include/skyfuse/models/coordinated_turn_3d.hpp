#pragma once
/// \file
/// A coordinated turn in the horizontal plane at a constant climb rate: the turning mode of the
/// station network's IMM. State x = [p; v; omega] in R^7; (px, vx, py, vy, omega) turn as
/// turn_kinematics.hpp says, pz' = pz + dt vz, vz' = vz. Like the paper-000 models, the process
/// noise is the per-step covariance Q = blkdiag(sigma_p^2 I3, sigma_v^2 I3, sigma_omega^2).

#include <array>
#include <string_view>

#include "skyfuse/core/types.hpp"
#include "skyfuse/models/kinematic_state.hpp"
#include "skyfuse/models/turn_kinematics.hpp"

namespace skyfuse {

class CoordinatedTurn3D {
 public:
  static constexpr std::string_view kKind = "coordinated_turn_3d";
  static constexpr int kDim = 7;
  using State = Vector<kDim>;

  static constexpr int kPosition = 0;
  static constexpr int kVelocity = 3;
  static constexpr int kTurnRate = 6;
  static constexpr std::array<int, kDim> kCommonIndex = {
      0, 1, 2, 3, 4, 5, KinematicState::kTurnRate};

  static constexpr std::array<std::string_view, 3> kNoiseFields = {"position_m", "velocity_mps",
                                                                   "turn_rate_radps"};
  using NoiseStd = std::array<double, kNoiseFields.size()>;

  CoordinatedTurn3D(double time_step_s, const NoiseStd& noise_std) : dt_(time_step_s) {
    const auto [position, velocity, turn_rate] = noise_std;
    process_noise_.setZero();
    process_noise_.diagonal() << Vector3::Constant(position * position),
        Vector3::Constant(velocity * velocity), turn_rate * turn_rate;
  }

  /// The model's state of a target with kinematics [p; v; a]: its position, velocity and the
  /// horizontal turn rate its acceleration implies, (vx ay - vy ax) / (vx^2 + vy^2).
  static State from_kinematics(const Vector<9>& k) {
    State x;
    const double speed_sq = k(3) * k(3) + k(4) * k(4);
    x << k.head<6>(), speed_sq > 0.0 ? (k(3) * k(7) - k(4) * k(6)) / speed_sq : 0.0;
    return x;
  }

  State propagate(const State& x) const {
    State out = x;
    propagate_turn(kTurn, dt_, x, out);
    out(2) = x(2) + dt_ * x(5);
    return out;
  }

  Covariance<kDim> jacobian(const State& x) const {
    Covariance<kDim> f = Covariance<kDim>::Identity();
    turn_jacobian(kTurn, dt_, x, f);
    f(2, 5) = dt_;
    return f;
  }

  const Covariance<kDim>& process_noise() const { return process_noise_; }

 private:
  // x, vx, y, vy, omega
  static constexpr TurnIndices kTurn{0, 3, 1, 4, kTurnRate};

  double dt_;
  Covariance<kDim> process_noise_;
};

}  // namespace skyfuse
