#pragma once
/// \file
/// The common state in which an IMM mixes planar models of different dimensions (CV 4, CA 6,
/// CT 5): x = [x, vx, y, vy, ax, ay, omega]. A model that lacks a component contributes mean 0
/// and variance 0 there, so mixing never invents acceleration or turn rate a mode did not
/// estimate; a mode reads back only the components it has.

#include <array>

namespace skyfuse {

struct PlanarState {
  static constexpr int kDim = 7;
  static constexpr int kX = 0;
  static constexpr int kVx = 1;
  static constexpr int kY = 2;
  static constexpr int kVy = 3;
  static constexpr int kAx = 4;
  static constexpr int kAy = 5;
  static constexpr int kTurnRate = 6;
};

}  // namespace skyfuse
