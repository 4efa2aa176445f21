#pragma once

#include "skyfuse/core/types.hpp"

namespace skyfuse::test {

/// A vector of `draw()`s, its last entry drawn first: the order the tests' seeds were chosen
/// under. Written out because `Vector3(d(), d(), d())` leaves the order to the compiler (GCC
/// evaluates a call's arguments last first, clang first first), and so would its draws.
template <int N, typename Draw>
Vector<N> draw_last_first(Draw&& draw) {
  Vector<N> v;
  for (int i = N - 1; i >= 0; --i) v(i) = draw();
  return v;
}

}  // namespace skyfuse::test
