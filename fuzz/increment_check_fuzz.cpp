// Fuzz target: check_increment on an information increment made of arbitrary doubles. It must
// never crash, and an increment it accepts must be one a peer can fuse: dQ and dy finite, dQ
// symmetric, and no eigenvalue of dQ below the check's own tolerance, -1e-9 times the largest
// magnitude. The eigenvalues are recomputed here by a different algorithm than the check's.
//
// Input: one byte choosing how dQ is made, then doubles (see fuzz_input.hpp).
//  - even: dQ is 45 doubles, its upper triangle as on the wire; then dy, 9 doubles.
//  - odd:  dQ = G^T G from a 3 x 9 G of 27 doubles, positive semi-definite up to rounding the
//          way a real H^T R^-1 H is, so that accepted matrices with extreme values are common;
//          then dy.

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "fuzz_input.hpp"
#include "skyfuse/validation/sample_checks.hpp"

namespace {

using skyfuse::Covariance;
using skyfuse::InformationIncrement;
using skyfuse::Matrix;

[[noreturn]] void finding(const char* what) {
  std::fprintf(stderr, "increment_check_fuzz: accepted an increment that %s\n", what);
  std::abort();
}

InformationIncrement<9> decode(skyfuse::fuzz::FuzzInput& in) {
  InformationIncrement<9> increment;
  if (in.byte() % 2 == 0) {
    increment.delta_information = in.symmetric<9>();
  } else {
    Matrix<3, 9> g;
    for (int r = 0; r < 3; ++r) g.row(r) = in.vector<9>().transpose();
    const Covariance<9> gram = g.transpose() * g;
    // Only the upper triangle travels.
    increment.delta_information = gram.selfadjointView<Eigen::Upper>();
  }
  increment.delta_vector = in.vector<9>();
  return increment;
}

// Eigenvalues of a symmetric matrix by cyclic Jacobi rotations: each rotation zeroes one
// off-diagonal pair, and sweeps repeat until nothing off the diagonal is left. Slow, but a
// few lines that share nothing with the check's tridiagonal QL, and accurate to a few ulps of
// the largest eigenvalue.
Eigen::Matrix<double, 9, 1> jacobi_eigenvalues(Covariance<9> a) {
  for (int sweep = 0; sweep < 100; ++sweep) {
    double off_diagonal = 0.0;
    for (int p = 0; p < 9; ++p) {
      for (int q = p + 1; q < 9; ++q) off_diagonal += a(p, q) * a(p, q);
    }
    if (off_diagonal <= 1e-40 * a.squaredNorm()) break;
    for (int p = 0; p < 9; ++p) {
      for (int q = p + 1; q < 9; ++q) {
        if (a(p, q) == 0.0) continue;
        // The rotation angle that zeroes a(p, q), as the smaller root of t^2 + 2 theta t = 1.
        const double theta = (a(q, q) - a(p, p)) / (2.0 * a(p, q));
        const double t = std::copysign(1.0, theta) / (std::abs(theta) + std::hypot(theta, 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0);
        const double s = t * c;
        for (int k = 0; k < 9; ++k) {  // A J
          const double kp = a(k, p);
          const double kq = a(k, q);
          a(k, p) = c * kp - s * kq;
          a(k, q) = s * kp + c * kq;
        }
        for (int k = 0; k < 9; ++k) {  // J^T (A J)
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
void verify_accepted(const InformationIncrement<9>& increment) {
  const Covariance<9>& dq = increment.delta_information;
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
  const auto eigenvalues = jacobi_eigenvalues(dq / largest_entry);
  const double smallest = eigenvalues.minCoeff();
  const double largest_magnitude = eigenvalues.cwiseAbs().maxCoeff();
  if (smallest < -(1e-9 + 1e-12) * largest_magnitude) {
    std::fprintf(stderr, "smallest eigenvalue %.17g, largest magnitude %.17g (scaled by %.17g)\n",
                 smallest, largest_magnitude, largest_entry);
    finding("has an eigenvalue below the tolerance");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  skyfuse::fuzz::FuzzInput in(data, size);
  const InformationIncrement<9> increment = decode(in);
  if (skyfuse::check_increment(increment) == std::nullopt) verify_accepted(increment);
  return 0;
}
