#include "skyfuse/models/constant_acceleration.hpp"

#include <gtest/gtest.h>

namespace skyfuse {
namespace {

TEST(ConstantAcceleration3D, PropagatesEachAxisWithTheKinematicEquations) {
  const ConstantAcceleration3D model(0.5, {});
  Vector<9> x;
  x << 1.0, 2.0, 3.0,    // p
      10.0, 20.0, 30.0,  // v
      2.0, -4.0, 6.0;    // a
  const Vector<9> next = model.propagate(x);
  for (int axis = 0; axis < 3; ++axis) {
    const double p = x(axis);
    const double v = x(3 + axis);
    const double a = x(6 + axis);
    EXPECT_DOUBLE_EQ(next(axis), p + 0.5 * v + 0.125 * a);
    EXPECT_DOUBLE_EQ(next(3 + axis), v + 0.5 * a);
    EXPECT_DOUBLE_EQ(next(6 + axis), a);
  }
}

TEST(ConstantAcceleration3D, ProcessNoiseIsBlockDiagonalPerStep) {
  const ConstantAcceleration3D model(0.02, {0.5, 0.1, 0.05});
  Vector<9> expected;
  expected << 0.25, 0.25, 0.25, 0.01, 0.01, 0.01, 0.0025, 0.0025, 0.0025;
  EXPECT_TRUE(model.process_noise().diagonal().isApprox(expected, 1e-15));
  const Covariance<9>& q = model.process_noise();
  EXPECT_EQ((q - Covariance<9>(q.diagonal().asDiagonal())).norm(), 0.0) << "off-diagonal terms";
}

// The block-wise covariance propagation is the dense F P F^T + Q with F = jacobian(), and the
// mean propagation is F x.
TEST(ConstantAcceleration3D, BlockPropagationIsTheDenseProduct) {
  const ConstantAcceleration3D model(0.02, {0.5, 0.1, 0.05});
  const Matrix<9, 9> a = Matrix<9, 9>::Random();
  const Covariance<9> p = a * a.transpose() + Covariance<9>::Identity();
  const Vector<9> x = Vector<9>::Random();
  const Covariance<9>& f = model.jacobian(x);
  const Covariance<9> dense = f * p * f.transpose() + model.process_noise();
  EXPECT_LT((model.propagate_covariance(p) - dense).norm(), 1e-13 * dense.norm());
  EXPECT_LT((model.propagate(x) - f * x).norm(), 1e-14 * x.norm());
}

}  // namespace
}  // namespace skyfuse
