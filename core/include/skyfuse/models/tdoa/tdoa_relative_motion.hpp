#pragma once
/// \file
/// Paper 002's relative state as a scenario's motion model, `tdoa_relative_constant_acceleration`:
/// BlockConstantAcceleration<3> over [dx, dy, d_t1] (block_constant_acceleration.hpp), in the
/// frame of the reference receiver at the origin, with one noise field, the standard deviation
/// of each acceleration's increment per step (the paper's q is its square). The position is
/// [dx, dy] (planar); d_t1 = |[dx, dy]| is a state of its own, not enforced. Its members are
/// compiled once, in tdoa_relative_motion.cpp: the registry, which every file of the processes
/// includes, includes this header.

#include <array>
#include <string_view>

#include "skyfuse/models/tdoa/block_constant_acceleration.hpp"

namespace skyfuse {

class TdoaRelativeMotion : public BlockConstantAcceleration<3> {
 public:
  static constexpr std::string_view kKind = "tdoa_relative_constant_acceleration";
  static constexpr std::array<std::string_view, 1> kNoiseFields = {"acceleration_mps2"};
  using NoiseStd = std::array<double, kNoiseFields.size()>;
  /// [dx, dy] is the position; entry 2 is the range d_t1, not a height.
  static constexpr int kPositionDim = 2;

  TdoaRelativeMotion(double time_step_s, const NoiseStd& noise_std);

  /// The state of the target's kinematics [p; v; a] (relative to the reference receiver):
  /// [dx, dy, d, dvx, dvy, d', dax, day, d''] with d = |dp|, d' = dp.dv / d and
  /// d'' = (|dv|^2 + dp.da - d'^2) / d, in the horizontal plane.
  static State from_kinematics(const Vector<9>& kinematics);

  /// `x` with its range entries d, d' and d'' derived from its own [dx, dy], rates and
  /// accelerations, as from_kinematics() derives the truth's. initial_estimate() applies it, so
  /// that an initial estimate starts with d = |dp| (SEEDS.md, paper 002: d0_hat = |dp0_hat|)
  /// rather than with a range error drawn apart from the position's.
  static State with_derived_range(const State& x);
};

}  // namespace skyfuse
