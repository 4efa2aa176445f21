#include "skyfuse/models/position_velocity.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <random>
#include <span>

#include "skyfuse/filters/kalman.hpp"
#include "skyfuse/fusion/increment_fusion.hpp"
#include "skyfuse/fusion/information_increment.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/sim/monte_carlo.hpp"
#include "support/numerical_jacobian.hpp"
#include "support/random_problems.hpp"

namespace skyfuse {
namespace {

using Sensor = PositionVelocity<9>;

TEST(PositionVelocity, PredictsThePositionAndVelocityOfTheState) {
  Vector<9> x;
  x << 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0;
  const Sensor sensor;
  EXPECT_EQ(sensor.predict(x), x.head<6>());
  const Jacobian<6, 9> h = sensor.jacobian(x);
  EXPECT_EQ(h.leftCols<6>(), Covariance<6>::Identity());
  EXPECT_EQ(h.rightCols<3>(), (Matrix<6, 3>::Zero()));
}

TEST(PositionVelocity, JacobianMatchesCentralDifferences) {
  std::mt19937 rng(3);
  const Sensor sensor;
  for (int trial = 0; trial < 20; ++trial) {
    Vector<9> x;
    x << test::random_vector3(rng, -3000.0, 3000.0), test::random_vector3(rng, -80.0, 80.0),
        test::random_vector3(rng, -5.0, 5.0);
    EXPECT_LE((sensor.jacobian(x) - test::numerical_jacobian(sensor, x)).cwiseAbs().maxCoeff(),
              1e-9);
  }
}

TEST(PositionVelocity, ReportsOnlyWhatAReceiverCanMeasure) {
  Vector<6> z;
  z << 100.0, -200.0, 300.0, 50.0, 0.0, -1.0;
  EXPECT_FALSE(Sensor::check_reported(z));
  EXPECT_EQ(Sensor::to_reported(z), z);
  Vector<6> far = z;
  far(0) = 2.0 * kMaxRangeM;
  EXPECT_EQ(Sensor::check_reported(far), DropKind::kOutOfRange);
  Vector<6> fast = z;
  fast(4) = 2.0 * kMaxSpeedMps;
  EXPECT_EQ(Sensor::check_reported(fast), DropKind::kOutOfRange);
  Vector<6> nan = z;
  nan(5) = std::nan("");
  EXPECT_EQ(Sensor::check_reported(nan), DropKind::kNonFinite);
}

// The update through the generic EKF is the textbook linear Kalman update, and the increment
// fused into the prior is the same update in information form.
TEST(PositionVelocity, UpdateAndIncrementAreTheKalmanUpdate) {
  std::mt19937 rng(11);
  const Sensor sensor;
  for (int trial = 0; trial < 20; ++trial) {
    const GaussianState<9> prior = test::random_prior(rng, Vector3(100.0, 200.0, 300.0));
    const Covariance<6> r = test::random_spd<6>(rng, 0.5, 9.0);
    Vector<6> z = sensor.predict(prior.mean);
    z.head<3>() += test::random_vector3(rng, -3.0, 3.0);
    z.tail<3>() += test::random_vector3(rng, -2.0, 2.0);

    const Jacobian<6, 9> h = sensor.jacobian(prior.mean);
    const Covariance<6> s = h * prior.covariance * h.transpose() + r;
    const Matrix<9, 6> k = prior.covariance * h.transpose() * s.inverse();
    const Vector<9> expected_mean = prior.mean + k * (z - h * prior.mean);
    const Covariance<9> expected_cov = (Covariance<9>::Identity() - k * h) * prior.covariance;

    GaussianState<9> updated = prior;
    ASSERT_EQ(update(updated, sensor, z, r).status, NumericalStatus::kOk);
    EXPECT_LE(test::relative_error(updated.mean, expected_mean), 1e-10);
    EXPECT_LE(test::relative_error(updated.covariance, expected_cov), 1e-9);

    InformationIncrement<9> increment;
    ASSERT_EQ(compute_increment(1, prior, sensor, z, r, increment), NumericalStatus::kOk);
    GaussianState<9> fused;
    const double weight = 1.0;
    ASSERT_EQ(fuse_increments<9>(prior, std::span(&increment, 1), std::span(&weight, 1), fused),
              NumericalStatus::kOk);
    EXPECT_LE(test::relative_error(fused.mean, expected_mean), 1e-9);
    EXPECT_LE(test::relative_error(fused.covariance, expected_cov), 1e-8);
  }
}

// A scenario names it by kind, with no site; the in-process run takes it from there.
constexpr const char* kGpsScenario = R"(
name: gps_only
seed: 7
time_step_s: 0.1
steps: 200
target:
  initial_position_m: [0.0, 0.0, 100.0]
  velocity_mps: [10.0, 5.0, 1.0]
stations:
  - {id: 1, sensor: {kind: position_velocity, noise_std: [3, 3, 3, 2, 2, 2]}}
  - {id: 2, sensor: {kind: position_velocity, noise_std: [5, 5, 5, 1, 1, 1]}}
measurement_noise: {scale: none}
filter:
  motion_model:
    kind: constant_acceleration_3d
    process_noise_std: {position_m: 0.1, velocity_mps: 0.1, acceleration_mps2: 0.1}
  initial_covariance_diag: 100.0
)";

TEST(PositionVelocity, AScenarioNamesItAndBothArchitecturesRunIt) {
  const Scenario scenario = parse_scenario(kGpsScenario, "gps.yaml");
  ASSERT_EQ(scenario.stations[0].sensor.kind, "position_velocity");
  const TruthTrajectory truth = generate_truth(scenario.target, scenario.target.speeds_mps[0],
                                               scenario.time_step_s, scenario.steps);
  double worst_difference = 0.0;
  double late_sq_error = 0.0;
  int late_steps = 0;
  simulate_run(scenario, truth, 2, 0, [&](const StepRecord& r) {
    worst_difference = std::max(worst_difference,
                                (r.central.mean.head<3>() - r.decentralised.mean.head<3>()).norm());
    if (r.step >= 100) {
      late_sq_error += (r.truth.head<3>() - r.decentralised.mean.head<3>()).squaredNorm();
      ++late_steps;
    }
  });
  EXPECT_LT(worst_difference, 1e-6);
  // Two receivers of 3 m and 5 m per axis: the filtered error is well inside one receiver's.
  EXPECT_LT(std::sqrt(late_sq_error / late_steps), 3.0 * std::sqrt(3.0));
}

TEST(PositionVelocity, AScenarioRefusesASiteForIt) {
  std::string yaml = kGpsScenario;
  const std::string from = "{id: 1, sensor:";
  yaml.replace(yaml.find(from), from.size(), "{id: 1, position_m: [0, 0, 0], sensor:");
  try {
    parse_scenario(yaml, "gps.yaml");
    FAIL() << "a site was accepted";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()),
              "gps.yaml: stations[0].position_m: a position_velocity sensor rides on the target "
              "and has no site; remove it (line 10)");
  }
}

}  // namespace
}  // namespace skyfuse
