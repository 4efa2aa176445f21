#pragma once
/// \file
/// Nearly-constant-velocity motion in 3-D (paper 003, eq. 1-2).
///
/// State x = [p; v] in R^6, each block (x, y, z):
///   F = [[I3, dt I3], [0, I3]] (p + dt v, v),   Q = blkdiag(sigma_p^2 I3, sigma_v^2 I3),
/// the per-step process noise exactly as the paper states it (not a continuous-time white-noise
/// acceleration model).

#include <array>
#include <string_view>

#include "skyfuse/core/types.hpp"
#include "skyfuse/models/linear_transition.hpp"

namespace skyfuse {

class ConstantVelocity3D : public LinearTransition<6> {
 public:
  /// The name a scenario gives this model.
  static constexpr std::string_view kKind = "constant_velocity_3d";
  static constexpr int kPosition = 0;
  static constexpr int kVelocity = 3;

  /// Per-step standard deviations of the process noise, per block, in the order (and under
  /// the names) a scenario gives them.
  static constexpr std::array<std::string_view, 2> kNoiseFields = {"position_m", "velocity_mps"};
  using NoiseStd = std::array<double, kNoiseFields.size()>;

  /// Where each component lives in the common state an IMM mixes in (kinematic_state.hpp).
  static constexpr std::array<int, kDim> kCommonIndex = {0, 1, 2, 3, 4, 5};

  ConstantVelocity3D(double time_step_s, const NoiseStd& noise_std) {
    const auto [position, velocity] = noise_std;
    const Matrix3 eye = Matrix3::Identity();
    transition_.block<3, 3>(kPosition, kVelocity) = time_step_s * eye;
    process_noise_.block<3, 3>(kPosition, kPosition) = position * position * eye;
    process_noise_.block<3, 3>(kVelocity, kVelocity) = velocity * velocity * eye;
  }

  /// The model's state of a target with kinematics [p; v; a]: its position and velocity.
  static State from_kinematics(const Vector<9>& kinematics) { return kinematics.head<kDim>(); }
};

}  // namespace skyfuse
