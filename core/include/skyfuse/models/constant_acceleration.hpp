#pragma once
/// \file
/// Nearly-constant-acceleration motion in 3-D (paper 000, eq. 1-2).
///
/// State x = [p; v; a] in R^9, each block (x, y, z). Per axis
///   A = [[1, dt, dt^2/2], [0, 1, dt], [0, 0, 1]],  F = A (x) I3,
/// and the process noise is the per-step covariance Q = blkdiag(Qp, Qv, Qa) with each block a
/// multiple of I3, exactly as the paper states it (not a continuous-time white-noise model).

#include <array>
#include <string_view>

#include "skyfuse/core/types.hpp"

namespace skyfuse {

class ConstantAcceleration3D {
 public:
  /// The name a scenario gives this model.
  static constexpr std::string_view kKind = "constant_acceleration_3d";
  static constexpr int kDim = 9;
  using State = Vector<kDim>;

  /// Index of the first component of each block in the state.
  static constexpr int kPosition = 0;
  static constexpr int kVelocity = 3;
  static constexpr int kAcceleration = 6;

  /// Per-step standard deviations of the process noise, one per kinematic block, in the order
  /// (and under the names) a scenario gives them.
  static constexpr std::array<std::string_view, 3> kNoiseFields = {"position_m", "velocity_mps",
                                                                   "acceleration_mps2"};
  using NoiseStd = std::array<double, kNoiseFields.size()>;

  /// Where each component lives in the common state an IMM mixes in (kinematic_state.hpp).
  static constexpr std::array<int, kDim> kCommonIndex = {0, 1, 2, 3, 4, 5, 6, 7, 8};

  ConstantAcceleration3D(double time_step_s, const NoiseStd& noise_std);

  /// The model's state of a target with kinematics [p; v; a] (world frame): all of them.
  static State from_kinematics(const Vector<9>& kinematics) { return kinematics; }

  /// Mean propagation x_{k+1} = F x_k, per block: p + dt v + dt^2/2 a, v + dt a, a.
  State propagate(const State& x) const;
  /// F P F^T + Q using F = A (x) I3: a weighted sum of 3x3 blocks, about a fifth of the
  /// multiplications of the dense product. Not symmetrised (the filter does that).
  Covariance<kDim> propagate_covariance(const Covariance<kDim>& p) const;
  /// dF/dx; the model is linear, so this is F wherever it is evaluated.
  const Covariance<kDim>& jacobian(const State& /*x*/) const { return transition_; }
  const Covariance<kDim>& process_noise() const { return process_noise_; }

 private:
  double time_step_s_;
  Covariance<kDim> transition_;
  Covariance<kDim> process_noise_;
};

}  // namespace skyfuse
