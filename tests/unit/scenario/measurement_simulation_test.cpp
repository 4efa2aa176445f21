#include "skyfuse/scenario/measurement_simulation.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "skyfuse/models/range_azimuth_elevation.hpp"

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

}  // namespace
}  // namespace skyfuse
