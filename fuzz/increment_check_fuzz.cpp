// Fuzz target: check_increment on an information increment made of arbitrary doubles. It must
// never crash, and an increment it accepts must be one a peer can fuse: dQ and dy finite, dQ
// symmetric, and no eigenvalue of dQ below the check's own tolerance, -1e-9 times the largest
// magnitude. The eigenvalues are recomputed here by a different algorithm than the check's.
//
// Input: one byte choosing the state dimension and how dQ is made, then doubles (see
// fuzz_input.hpp). The byte / 2 picks a registered motion model (modulo their count; 0, the
// first, is constant_acceleration_3d, whose N = 9 the seeds were made for), whose dimension N
// the increment has, as on the wire of a run of that model.
//  - even: dQ is N (N + 1) / 2 doubles, its upper triangle as on the wire; then dy, N doubles.
//  - odd:  dQ = G^T G from a 3 x N G of 3 N doubles, positive semi-definite up to rounding the
//          way a real H^T R^-1 H is, so that accepted matrices with extreme values are common;
//          then dy.

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <type_traits>

#include "fuzz_input.hpp"
#include "skyfuse/registry/registry.hpp"
#include "skyfuse/validation/sample_checks.hpp"

namespace {

using skyfuse::Covariance;
using skyfuse::InformationIncrement;
using skyfuse::Matrix;

[[noreturn]] void finding(const char* what) {
  std::fprintf(stderr, "increment_check_fuzz: accepted an increment that %s\n", what);
  std::abort();
}

template <int N>
InformationIncrement<N> decode(skyfuse::fuzz::FuzzInput& in, bool gram_form) {
  InformationIncrement<N> increment;
  if (!gram_form) {
    increment.delta_information = in.symmetric<N>();
  } else {
    Matrix<3, N> g;
    for (int r = 0; r < 3; ++r) g.row(r) = in.vector<N>().transpose();
    const Covariance<N> gram = g.transpose() * g;
    // Only the upper triangle travels.
    increment.delta_information = gram.template selfadjointView<Eigen::Upper>();
  }
  increment.delta_vector = in.vector<N>();
  return increment;
}

// Eigenvalues of a symmetric matrix by cyclic Jacobi rotations: each rotation zeroes one
// off-diagonal pair, and sweeps repeat until nothing off the diagonal is left. Slow, but a
// few lines that share nothing with the check's tridiagonal QL, and accurate to a few ulps of
// the largest eigenvalue.
template <int N>
Eigen::Matrix<double, N, 1> jacobi_eigenvalues(Covariance<N> a) {
  for (int sweep = 0; sweep < 100; ++sweep) {
    double off_diagonal = 0.0;
    for (int p = 0; p < N; ++p) {
      for (int q = p + 1; q < N; ++q) off_diagonal += a(p, q) * a(p, q);
    }
    if (off_diagonal <= 1e-40 * a.squaredNorm()) break;
    for (int p = 0; p < N; ++p) {
      for (int q = p + 1; q < N; ++q) {
        if (a(p, q) == 0.0) continue;
        // The rotation angle that zeroes a(p, q), as the smaller root of t^2 + 2 theta t = 1.
        const double theta = (a(q, q) - a(p, p)) / (2.0 * a(p, q));
        const double t = std::copysign(1.0, theta) / (std::abs(theta) + std::hypot(theta, 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0);
        const double s = t * c;
        for (int k = 0; k < N; ++k) {  // A J
          const double kp = a(k, p);
          const double kq = a(k, q);
          a(k, p) = c * kp - s * kq;
          a(k, q) = s * kp + c * kq;
        }
        for (int k = 0; k < N; ++k) {  // J^T (A J)
          const double pk = a(p, k);
          const double qk = a(q, k);
          a(p, k) = c * pk - s * qk;
          a(q, k) = s * pk + c * qk;
        }
      }
    }
  }
  return a.diagonal();
}

// The check's promise, verified on dQ scaled to a largest entry of 1 (eigenvalues of a scaled
// matrix are the scaled eigenvalues, and nothing can overflow). The reference and the check may
// differ by a few ulps of the largest eigenvalue, hence 1e-12 of slack on top of the check's
// 1e-9.
template <int N>
void verify_accepted(const InformationIncrement<N>& increment) {
  const Covariance<N>& dq = increment.delta_information;
  if (!dq.allFinite() || !increment.delta_vector.allFinite()) finding("is not finite");
  if (dq != dq.transpose()) finding("is not symmetric");
  // 256 accepted increments (the most stations a run has) must sum to a finite matrix.
  if (!(256.0 * dq.cwiseAbs().maxCoeff() < std::numeric_limits<double>::max()) ||
      !(256.0 * increment.delta_vector.cwiseAbs().maxCoeff() <
        std::numeric_limits<double>::max())) {
    finding("is large enough to overflow a fused sum");
  }
  const double largest_entry = dq.cwiseAbs().maxCoeff();
  if (largest_entry == 0.0) return;
  const auto eigenvalues = jacobi_eigenvalues<N>(dq / largest_entry);
  const double smallest = eigenvalues.minCoeff();
  const double largest_magnitude = eigenvalues.cwiseAbs().maxCoeff();
  if (smallest < -(1e-9 + 1e-12) * largest_magnitude) {
    std::fprintf(stderr, "smallest eigenvalue %.17g, largest magnitude %.17g (scaled by %.17g)\n",
                 smallest, largest_magnitude, largest_entry);
    finding("has an eigenvalue below the tolerance");
  }
}

}  // namespace

// Calls f(std::integral_constant<int, N>{}) with the state dimension of the index-th
// registered motion model.
template <typename... Models, typename F>
void with_model_dimension(skyfuse::ModelList<Models...> /*list*/, int index, F f) {
  int i = 0;
  ((i++ == index ? (f(std::integral_constant<int, Models::kDim>{}), 0) : 0), ...);
}

template <typename... Models>
constexpr int model_count(skyfuse::ModelList<Models...> /*list*/) {
  return sizeof...(Models);
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  skyfuse::fuzz::FuzzInput in(data, size);
  const std::uint8_t selector = in.byte();
  const int model = (selector / 2) % model_count(skyfuse::MotionModels{});
  with_model_dimension(skyfuse::MotionModels{}, model, [&]<int N>(std::integral_constant<int, N>) {
    const InformationIncrement<N> increment = decode<N>(in, selector % 2 == 1);
    if (skyfuse::check_increment(increment) == std::nullopt) verify_accepted(increment);
  });
  return 0;
}
