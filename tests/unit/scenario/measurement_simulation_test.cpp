#include "skyfuse/scenario/measurement_simulation.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/models/tdoa/tdoa_relative_motion.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/scenario/truth.hpp"

namespace skyfuse {
namespace {

using Sensor = RangeAzimuthElevation<9>;

// The true kinematics [p; v; a] of a target at p, at rest.
Vector<9> at(const Vector3& p) {
  Vector<9> x = Vector<9>::Zero();
  x.head<3>() = p;
  return x;
}

// Straight above a station the true elevation is pi/2, and half of all noise draws point past
// it. A sensor reports no such angle, and every receiver refuses one: the simulation must not
// produce it.
TEST(SimulatedMeasurement, ElevationStaysWithinWhatASensorReportsAtTheZenith) {
  const Sensor sensor(Vector3(0.0, 0.0, 0.0));
  const Vector3 overhead(0.0, 0.0, 500.0);
  const Covariance<3> noise = Vector3(0.1 * 0.1, 0.01 * 0.01, 0.01 * 0.01).asDiagonal();
  int at_zenith = 0;
  for (std::uint64_t step = 0; step < 2000; ++step) {
    const Vector3 z = simulate_measurement(sensor, at(overhead), noise, 11, 0, 1, step);
    ASSERT_LE(std::abs(z(Sensor::kElevation)), std::numbers::pi / 2.0) << "step " << step;
    ASSERT_FALSE(Sensor::check_reported(z)) << "step " << step;
    if (z(Sensor::kElevation) == std::numbers::pi / 2.0) ++at_zenith;
  }
  // About half the draws point past the zenith and are held at it.
  EXPECT_GT(at_zenith, 800);
  EXPECT_LT(at_zenith, 1200);
}

// Away from the zenith the noise is left as drawn: the same numbers as before the bound.
TEST(SimulatedMeasurement, ElevationBelowTheZenithIsTheTruthPlusTheDrawnNoise) {
  const Sensor sensor(Vector3(0.0, 0.0, 0.0));
  const Vector3 aircraft(800.0, 300.0, 400.0);
  const Covariance<3> noise = Vector3(0.1 * 0.1, 0.01 * 0.01, 0.01 * 0.01).asDiagonal();
  const Vector3 truth = sensor.measure_position(aircraft);
  double sum = 0.0;
  double sum_sq = 0.0;
  constexpr int kDraws = 4000;
  for (std::uint64_t step = 0; step < kDraws; ++step) {
    const double e =
        simulate_measurement(sensor, at(aircraft), noise, 11, 0, 1, step)(Sensor::kElevation) -
        truth(Sensor::kElevation);
    sum += e;
    sum_sq += e * e;
  }
  EXPECT_NEAR(sum / kDraws, 0.0, 4.0 * 0.01 / std::sqrt(kDraws));
  EXPECT_NEAR(std::sqrt(sum_sq / kDraws), 0.01, 0.0005);
}

// Paper 002's relative state carries the range d_t1 = |dp| as an entry of its own. SEEDS.md
// starts the estimate at d0_hat = |dp0_hat|: its range, the range's rate and acceleration follow
// from its own position, velocity and acceleration, not from draws of their own, which would
// start it with d_hat != |dp_hat| (by 300 m, one sigma); dx, dy, their rates and accelerations
// keep their draws.
TEST(InitialEstimate, Paper002sRangeFollowsTheEstimatesOwnPosition) {
  const Scenario s = load_scenario_file(SKYFUSE_SOURCE_DIR "/scenarios/paper002.yaml");
  const Vector<9> x0 =
      generate_truth(s.target, s.target.speeds_mps.front(), s.time_step_s, 1).states.front();
  for (std::uint64_t run = 0; run < 5; ++run) {
    const Vector<9> mean = initial_estimate<TdoaRelativeMotion>(s, x0, run).mean;
    const Vector<9> drawn = TdoaRelativeMotion::from_kinematics(x0) + initial_state_error(s, run);
    for (int i : {0, 1, 3, 4, 6, 7}) EXPECT_EQ(mean(i), drawn(i)) << "run " << run << ", " << i;
    const Vector<2> p = mean.segment<2>(0);
    const Vector<2> v = mean.segment<2>(3);
    EXPECT_NEAR(mean(2), p.norm(), 1e-9 * p.norm()) << "run " << run;
    EXPECT_NEAR(mean(5), p.dot(v) / p.norm(), 1e-9 * v.norm()) << "run " << run;
  }
}

}  // namespace
}  // namespace skyfuse
