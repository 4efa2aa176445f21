#include "support/random_problems.hpp"

#include <Eigen/QR>

namespace skyfuse::test {

template <int N>
Covariance<N> random_spd(std::mt19937& rng, double lo, double hi) {
  std::normal_distribution<double> n(0.0, 1.0);
  Covariance<N> a;
  for (int i = 0; i < N; ++i) {
    for (int j = 0; j < N; ++j) a(i, j) = n(rng);
  }
  const Eigen::HouseholderQR<Covariance<N>> qr(a);
  const Covariance<N> q = qr.householderQ();
  std::uniform_real_distribution<double> u(lo, hi);
  Vector<N> eig;
  for (int i = 0; i < N; ++i) eig(i) = u(rng);
  Covariance<N> spd = q * eig.asDiagonal() * q.transpose();
  symmetrize(spd);
  return spd;
}

// The sizes the tests draw; another is a line here.
template Covariance<3> random_spd<3>(std::mt19937&, double, double);
template Covariance<6> random_spd<6>(std::mt19937&, double, double);
template Covariance<9> random_spd<9>(std::mt19937&, double, double);

}  // namespace skyfuse::test
