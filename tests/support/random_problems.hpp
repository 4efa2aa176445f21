#pragma once
// Random but reproducible test problems: SPD covariances, priors near a target, stations
// around it. Each test seeds its own std::mt19937 so that failures replay.

#include <random>

#include "skyfuse/core/types.hpp"
#include "support/draw_last_first.hpp"

namespace skyfuse::test {

inline Vector3 random_vector3(std::mt19937& rng, double lo, double hi) {
  std::uniform_real_distribution<double> u(lo, hi);
  return draw_last_first<3>([&] { return u(rng); });
}

/// SPD matrix with eigenvalues in [lo, hi]: a random rotation of a random positive diagonal.
/// Compiled once, in random_problems.cpp, for the sizes the tests draw (3, 6 and 9): a
/// fixed-size Householder QR cost every test file that drew one seconds of compiling a size.
template <int N>
Covariance<N> random_spd(std::mt19937& rng, double lo, double hi);

/// An N-state estimate: mean entries of spread 100, covariance eigenvalues in [0.01, 50].
template <int N>
GaussianState<N> random_state(std::mt19937& rng) {
  GaussianState<N> s;
  std::normal_distribution<double> n(0.0, 100.0);
  for (int i = 0; i < N; ++i) s.mean(i) = n(rng);
  s.covariance = random_spd<N>(rng, 0.01, 50.0);
  return s;
}

/// A 9-state prior whose position lies near `position`.
inline GaussianState<9> random_prior(std::mt19937& rng, const Vector3& position) {
  GaussianState<9> prior;
  prior.mean.head<3>() = position + random_vector3(rng, -2.0, 2.0);
  prior.mean.segment<3>(3) = random_vector3(rng, -80.0, 80.0);
  prior.mean.tail<3>() = random_vector3(rng, -3.0, 3.0);
  prior.covariance = random_spd<9>(rng, 0.05, 4.0);
  return prior;
}

/// Relative Frobenius distance |a - b| / max(|b|, floor).
template <typename A, typename B>
double relative_error(const A& a, const B& b, double floor = 1e-300) {
  return (a - b).norm() / std::max(b.norm(), floor);
}

}  // namespace skyfuse::test
