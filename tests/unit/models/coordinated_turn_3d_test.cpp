#include "skyfuse/models/coordinated_turn_3d.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace skyfuse {
namespace {

constexpr double kDt = 0.02;

Covariance<7> numerical_jacobian(const CoordinatedTurn3D& model, const Vector<7>& x) {
  Covariance<7> j;
  for (int i = 0; i < 7; ++i) {
    const double step = 1e-6 * std::max(1.0, std::abs(x(i)));
    Vector<7> plus = x;
    Vector<7> minus = x;
    plus(i) += step;
    minus(i) -= step;
    j.col(i) = (model.propagate(plus) - model.propagate(minus)) / (2.0 * step);
  }
  return j;
}

TEST(CoordinatedTurn3D, TurnsHorizontallyAndClimbsAtConstantRate) {
  const CoordinatedTurn3D model(kDt, {0.0, 0.0, 0.0});
  Vector<7> x;
  x << 0.0, 0.0, 100.0, 80.0, 0.0, 2.0, 0.05;  // 80 m/s east, climbing 2 m/s, 0.05 rad/s left
  Vector<7> after = x;
  for (int k = 0; k < 100; ++k) after = model.propagate(after);
  const double angle = 0.05 * 100 * kDt;
  EXPECT_NEAR(std::atan2(after(4), after(3)), angle, 1e-12);
  EXPECT_NEAR(std::hypot(after(3), after(4)), 80.0, 1e-10);
  EXPECT_NEAR(after(0), 80.0 / 0.05 * std::sin(angle), 1e-9);
  EXPECT_NEAR(after(1), 80.0 / 0.05 * (1.0 - std::cos(angle)), 1e-9);
  EXPECT_NEAR(after(2), 100.0 + 2.0 * 100 * kDt, 1e-12);
}

TEST(CoordinatedTurn3D, JacobianMatchesCentralDifferences) {
  const CoordinatedTurn3D model(kDt, {0.5, 0.1, 0.002});
  for (const double omega : {0.05, -0.3, 1e-5, 0.0}) {
    Vector<7> x;
    x << 10.0, -20.0, 300.0, 70.0, 40.0, -1.0, omega;
    EXPECT_LT((model.jacobian(x) - numerical_jacobian(model, x)).cwiseAbs().maxCoeff(), 1e-7)
        << "omega " << omega;
  }
}

TEST(CoordinatedTurn3D, TurnRateOfKinematicsIsTheHorizontalCurvatureRate) {
  Vector<9> k;
  k << 1.0, 2.0, 3.0, 80.0, 0.0, 1.0, 0.0, 4.0, 0.5;  // centripetal 4 m/s^2 to the left
  const Vector<7> x = CoordinatedTurn3D::from_kinematics(k);
  EXPECT_EQ(x.head<6>(), k.head<6>());
  EXPECT_DOUBLE_EQ(x(6), 4.0 / 80.0);
  const CoordinatedTurn3D model(kDt, {0.5, 0.1, 0.002});
  EXPECT_EQ(
      model.process_noise().diagonal(),
      (Vector<7>() << 0.25, 0.25, 0.25, 0.1 * 0.1, 0.1 * 0.1, 0.1 * 0.1, 0.002 * 0.002).finished());
}

}  // namespace
}  // namespace skyfuse
