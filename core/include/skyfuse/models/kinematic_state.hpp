#pragma once
/// \file
/// The common state in which an IMM mixes 3-D models of different dimensions (CV 6, CA 9,
/// CT 7): x = [p; v; a; omega], omega the horizontal turn rate. As in the planar case
/// (planar/planar_state.hpp), a model that lacks a component counts as mean 0, variance 0 there.

namespace skyfuse {

struct KinematicState {
  static constexpr int kDim = 10;
  static constexpr int kPosition = 0;
  static constexpr int kVelocity = 3;
  static constexpr int kAcceleration = 6;
  static constexpr int kTurnRate = 9;
};

}  // namespace skyfuse
