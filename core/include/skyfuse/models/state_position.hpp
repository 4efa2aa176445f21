#pragma once
/// \file
/// Where a state holds the target's position: its first kPositionDim entries. Every 3-D model
/// keeps [x, y, z] there (kPositionDim 3, the default); a planar model keeps [x, y] and its
/// height counts as 0. Errors and differences of positions go through here, so that a model
/// whose third entry is not a height (paper 002's range d_t1) is compared by its position only.

#include "skyfuse/core/types.hpp"

namespace skyfuse {

template <typename Model>
constexpr int position_dim() {
  if constexpr (requires { Model::kPositionDim; }) {
    return Model::kPositionDim;
  } else {
    return 3;
  }
}

/// How many leading state entries `Sensor` reads as the target's position: 3 unless it says
/// otherwise (paper 002's TDOA receiver reads the horizontal 2). A sensor runs on a model whose
/// position_dim is at least its own: a radar reads nothing meaningful from paper 002's
/// [dx, dy, d_t1, ...].
template <typename Sensor>
constexpr int sensor_position_dim() {
  if constexpr (requires { Sensor::kPositionDim; }) {
    return Sensor::kPositionDim;
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
