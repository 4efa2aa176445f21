#include "skyfuse/models/tdoa/block_constant_acceleration.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

namespace skyfuse {
namespace {

TEST(BlockConstantAcceleration, CarriesAConstantAccelerationExactly) {
  const BlockConstantAcceleration<3> model(0.002, 0.01);
  Vector<9> x;
  x << 100.0, -50.0, 3000.0, 5.0, -2.0, 1.5, 0.3, -0.2, 0.01;
  Vector<9> propagated = x;
  constexpr int kSteps = 500;
  for (int k = 0; k < kSteps; ++k) propagated = model.propagate(propagated);
  const double t = 0.002 * kSteps;
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(propagated(i), x(i) + x(3 + i) * t + 0.5 * x(6 + i) * t * t, 1e-9) << i;
    EXPECT_NEAR(propagated(3 + i), x(3 + i) + x(6 + i) * t, 1e-12) << i;
    EXPECT_EQ(propagated(6 + i), x(6 + i)) << i;
  }
}

TEST(BlockConstantAcceleration, ItsProcessNoiseIsQTimesGGTransposed) {
  const double t = 0.002;
  const BlockConstantAcceleration<2> model(t, 0.01);
  // One axis: G = [t^2/2, t, 1], so Q = 0.01 [[t^4/4, t^3/2, t^2/2], [., t^2, t], [., ., 1]].
  const Covariance<6>& q = model.process_noise();
  EXPECT_DOUBLE_EQ(q(0, 0), 0.01 * t * t * t * t / 4.0);
  EXPECT_DOUBLE_EQ(q(0, 2), 0.01 * t * t * t / 2.0);
  EXPECT_DOUBLE_EQ(q(2, 4), 0.01 * t);
  EXPECT_DOUBLE_EQ(q(4, 4), 0.01);
  EXPECT_EQ(q(0, 1), 0.0);  // the axes are independent
  EXPECT_EQ(q, q.transpose());
  const Eigen::SelfAdjointEigenSolver<Covariance<6>> eigen(q);
  EXPECT_GT(eigen.eigenvalues().minCoeff(), -1e-12 * eigen.eigenvalues().maxCoeff());
}

TEST(BlockConstantAcceleration, ItsBlockPropagationIsFPFTransposedPlusQ) {
  const BlockConstantAcceleration<3> model(0.002, 0.01);
  Covariance<9> p = Covariance<9>::Identity();
  for (int i = 0; i < 9; ++i) {
    for (int j = 0; j < 9; ++j) p(i, j) += 0.01 * (i + 1) * (j + 1);
  }
  const Covariance<9> f = model.jacobian(Vector<9>::Zero());
  const Covariance<9> dense = f * p * f.transpose() + model.process_noise();
  EXPECT_LT((model.propagate_covariance(p) - dense).cwiseAbs().maxCoeff(), 1e-15);
}

}  // namespace
}  // namespace skyfuse
