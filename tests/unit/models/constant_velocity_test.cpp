#include "skyfuse/models/constant_velocity.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "skyfuse/filters/kalman.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/sim/monte_carlo.hpp"

namespace skyfuse {
namespace {

TEST(ConstantVelocity3D, PropagatesEachAxisAtConstantVelocity) {
  const ConstantVelocity3D model(0.5, {0.0, 0.0});
  Vector<6> x;
  x << 1.0, 2.0, 3.0, 10.0, -20.0, 30.0;
  const Vector<6> next = model.propagate(x);
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_DOUBLE_EQ(next(axis), x(axis) + 0.5 * x(3 + axis));
    EXPECT_DOUBLE_EQ(next(3 + axis), x(3 + axis));
  }
}

TEST(ConstantVelocity3D, ProcessNoiseIsPapers003PerStepDiagonal) {
  // Paper 003: Q = diag(5^2, 5^2, 5^2, 3^2, 3^2, 3^2).
  const ConstantVelocity3D model(0.5, {5.0, 3.0});
  Vector<6> expected;
  expected << 25.0, 25.0, 25.0, 9.0, 9.0, 9.0;
  EXPECT_EQ(model.process_noise(), Covariance<6>(expected.asDiagonal()));
}

TEST(ConstantVelocity3D, PredictionIsFPFtPlusQ) {
  const ConstantVelocity3D model(0.5, {5.0, 3.0});
  Covariance<6> f = Covariance<6>::Identity();
  f.topRightCorner<3, 3>() = 0.5 * Matrix3::Identity();
  EXPECT_EQ(model.jacobian(Vector<6>::Zero()), f);

  GaussianState<6> state;
  state.mean << 1.0, 2.0, 3.0, 4.0, 5.0, 6.0;
  state.covariance = Covariance<6>::Identity();
  state.covariance(0, 3) = state.covariance(3, 0) = 0.3;
  const Covariance<6> expected = f * state.covariance * f.transpose() + model.process_noise();
  predict(state, model);
  EXPECT_LE((state.covariance - expected).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_EQ(state.covariance, state.covariance.transpose());
}

TEST(ConstantVelocity3D, TakesPositionAndVelocityOfTheKinematics) {
  Vector<9> kinematics;
  kinematics << 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0;
  EXPECT_EQ(ConstantVelocity3D::from_kinematics(kinematics), kinematics.head<6>());
}

// A scenario names it; both architectures run it with ground stations and with a receiver on
// the target, and agree.
TEST(ConstantVelocity3D, AScenarioNamesItAndBothArchitecturesRunIt) {
  const std::string yaml = R"(
name: cv
seed: 3
time_step_s: 0.1
steps: 300
target:
  initial_position_m: [0.0, 0.0, 100.0]
  velocity_mps: [10.0, 5.0, 1.0]
stations:
  - {id: 1, position_m: [500.0, 0.0, 0.0], sensor: {kind: range_azimuth_elevation, noise_std: [1.0, 0.01, 0.01]}}
  - {id: 2, position_m: [0.0, 500.0, 0.0], sensor: {kind: range_azimuth_elevation, noise_std: [1.0, 0.01, 0.01]}}
measurement_noise: {scale: none}
filter:
  motion_model:
    kind: constant_velocity_3d
    process_noise_std: {position_m: 0.01, velocity_mps: 0.01}
  initial_covariance_diag: [100, 100, 100, 10, 10, 10]
)";
  const Scenario scenario = parse_scenario(yaml, "cv.yaml");
  EXPECT_EQ(scenario.filter.motion_model.kind, "constant_velocity_3d");
  const TruthTrajectory truth = generate_truth(scenario.target, scenario.target.speeds_mps[0],
                                               scenario.time_step_s, scenario.steps);
  double worst = 0.0;
  double last_error = 0.0;
  simulate_run(scenario, truth, 2, 0, [&](const StepRecord& r) {
    ASSERT_EQ(r.decentralised.mean.size(), 6);
    worst = std::max(worst, (r.central.mean - r.decentralised.mean).head<3>().norm());
    last_error = (r.truth.head<3>() - r.decentralised.mean.head<3>()).norm();
  });
  EXPECT_LT(worst, 1e-6);
  EXPECT_LT(last_error, 3.0) << "a straight flight is what this model tracks best";
}

}  // namespace
}  // namespace skyfuse
