// The stacked EKF's Cholesky against Eigen's LLT on the same matrices: on both sides of the size
// at which it hands over to Eigen's blocked factorisation, with several right-hand sides and
// with the forward half alone; and a matrix that is not positive definite is refused.
#include "skyfuse/core/stacked_cholesky.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace skyfuse {
namespace {

using Factor = StackedCholesky<3, 3>;

// A well-conditioned SPD matrix of size n with only its lower triangle filled (the upper holds
// garbage, which the factorisation must not read).
Eigen::MatrixXd random_spd_lower(Eigen::Index n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd a(n, n);
  for (Eigen::Index c = 0; c < n; ++c) {
    for (Eigen::Index r = 0; r < n; ++r) a(r, c) = normal(rng);
  }
  Eigen::MatrixXd spd =
      a * a.transpose() + static_cast<double>(n) * Eigen::MatrixXd::Identity(n, n);
  spd.triangularView<Eigen::StrictlyUpper>().setConstant(1e300);
  return spd;
}

Eigen::MatrixXd full(const Eigen::MatrixXd& lower) {
  Eigen::MatrixXd f = lower.triangularView<Eigen::Lower>();
  f.triangularView<Eigen::StrictlyUpper>() =
      lower.triangularView<Eigen::StrictlyLower>().transpose();
  return f;
}

class StackedCholeskySizes : public ::testing::TestWithParam<int> {};

TEST_P(StackedCholeskySizes, SolvesLikeEigensLlt) {
  const Eigen::Index n = 3 * GetParam();
  const Eigen::MatrixXd lower = random_spd_lower(n, static_cast<std::uint32_t>(n));
  const Eigen::MatrixXd s = full(lower);
  const Eigen::LLT<Eigen::MatrixXd> reference(s);

  Factor factor;
  ASSERT_TRUE(factor.compute(lower));

  Factor::RowMajorRhs b = Factor::RowMajorRhs::Random(n, 3);
  const Eigen::MatrixXd expected = reference.solve(Eigen::MatrixXd(b));
  factor.solve_in_place(b);
  EXPECT_LT((Eigen::MatrixXd(b) - expected).norm(), 1e-12 * expected.norm());

  // |L^-1 v|^2 = v^T S^-1 v, whatever the (unique) factor's layout.
  Eigen::VectorXd v = Eigen::VectorXd::Random(n);
  const double quadratic = v.dot(reference.solve(v));
  factor.forward_solve_in_place(v);
  EXPECT_NEAR(v.squaredNorm(), quadratic, 1e-12 * quadratic);
}

// 1 .. 11 stations take the block algorithm; 86 and more Eigen's blocked LLT.
INSTANTIATE_TEST_SUITE_P(Stations, StackedCholeskySizes,
                         ::testing::Values(1, 2, 5, 11, 85, 86, 100));

TEST(StackedCholesky, RefusesAMatrixThatIsNotPositiveDefinite) {
  for (const int stations : {4, 90}) {
    const Eigen::Index n = 3 * stations;
    Eigen::MatrixXd lower = random_spd_lower(n, 7);
    lower(n - 2, n - 2) = -1.0;  // a negative variance in the last block
    Factor factor;
    EXPECT_FALSE(factor.compute(lower)) << stations << " stations";
  }
}

// A NaN is not positive: refused by the block algorithm and by the hand-over to Eigen's LLT
// alike (whose pivot test, x <= 0, a NaN passes).
TEST(StackedCholesky, RefusesAMatrixWithANaN) {
  for (const int stations : {4, 90}) {
    const Eigen::Index n = 3 * stations;
    Eigen::MatrixXd lower = random_spd_lower(n, 7);
    lower(n - 1, 1) = std::nan("");
    Factor factor;
    EXPECT_FALSE(factor.compute(lower)) << stations << " stations";
  }
}

TEST(StackedCholesky, ReusesItsBuffersForASmallerMatrix) {
  Factor factor;
  ASSERT_TRUE(factor.compute(random_spd_lower(30, 1)));
  const Eigen::MatrixXd lower = random_spd_lower(9, 2);
  ASSERT_TRUE(factor.compute(lower));
  Factor::RowMajorRhs b = Factor::RowMajorRhs::Random(9, 3);
  const Eigen::MatrixXd expected = full(lower).llt().solve(Eigen::MatrixXd(b));
  factor.solve_in_place(b);
  EXPECT_LT((Eigen::MatrixXd(b) - expected).norm(), 1e-12 * expected.norm());
}

}  // namespace
}  // namespace skyfuse
