#pragma once
/// \file
/// Where a state holds the target's position: its first kPositionDim entries. Every 3-D model
/// keeps [x, y, z] there (kPositionDim 3, the default); a planar model keeps [x, y] and its
/// height counts as 0. Errors and differences of positions go through here, so that a model
/// whose third entry is not a height (paper 002's range d_t1) is compared by its position only.

#include "skyfuse/core/types.hpp"

namespace skyfuse {

/// How many leading state entries hold the target's position, for a motion model (what it
/// keeps), or for a sensor (what it reads): its kPositionDim, 3 unless it says otherwise (a
/// planar model keeps 2; paper 002's TDOA receiver reads the horizontal 2). A sensor runs on a
/// model whose position_dim is at least its own: a radar reads nothing meaningful from paper
/// 002's [dx, dy, d_t1, ...].
template <typename ModelOrSensor>
constexpr int position_dim() {
  if constexpr (requires { ModelOrSensor::kPositionDim; }) {
    return ModelOrSensor::kPositionDim;
  } else {
    return 3;
  }
}

/// The position in a state of `Model`.
template <typename Model, typename Derived>
Vector3 state_position(const Eigen::MatrixBase<Derived>& x) {
  constexpr int kDim = position_dim<Model>();
  Vector3 p = Vector3::Zero();
  p.template head<kDim>() = x.template head<kDim>();
  return p;
}

/// The same for a model known only by its position_dim (registry/part_info.hpp).
template <typename Derived>
Vector3 state_position(const Eigen::MatrixBase<Derived>& x, int position_dim) {
  Vector3 p = Vector3::Zero();
  for (int i = 0; i < position_dim; ++i) p(i) = x(i);
  return p;
}

}  // namespace skyfuse
