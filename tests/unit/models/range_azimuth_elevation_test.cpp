#include "skyfuse/models/range_azimuth_elevation.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include "support/numerical_jacobian.hpp"
#include "support/random_problems.hpp"

namespace skyfuse {
namespace {

using Sensor = RangeAzimuthElevation<9>;

void expect_jacobian_matches(const Sensor& sensor, const Vector<9>& x) {
  const Jacobian<3, 9> analytic = sensor.jacobian(x);
  const Jacobian<3, 9> numeric = test::numerical_jacobian(sensor, x);
  for (int row = 0; row < 3; ++row) {
    EXPECT_LE(test::relative_error(analytic.row(row), numeric.row(row)), 1e-6)
        << "row " << row << " at x = " << x.transpose() << "\nanalytic " << analytic.row(row)
        << "\nnumeric  " << numeric.row(row);
  }
}

TEST(RangeAzimuthElevation, JacobianMatchesFiniteDifferencesAtRandomPoints) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 500; ++trial) {
    const Sensor sensor(test::random_vector3(rng, -2000.0, 2000.0));
    Vector<9> x;
    x << sensor.station_position() + test::random_vector3(rng, -3000.0, 3000.0),
        test::random_vector3(rng, -80.0, 80.0), test::random_vector3(rng, -5.0, 5.0);
    expect_jacobian_matches(sensor, x);
  }
}

TEST(RangeAzimuthElevation, JacobianMatchesFiniteDifferencesNearTheAzimuthCut) {
  // Target due -x of the station: azimuth at +-pi, where atan2 jumps.
  const Sensor sensor(Vector3(100.0, -50.0, 10.0));
  for (double dy : {1e-3, -1e-3, 1e-2, -1e-2, 0.5, -0.5}) {
    for (double dz : {-200.0, 0.0, 300.0}) {
      Vector<9> x = Vector<9>::Zero();
      x.head<3>() = sensor.station_position() + Vector3(-1500.0, dy, dz);
      expect_jacobian_matches(sensor, x);
    }
  }
}

TEST(RangeAzimuthElevation, MeasuresTheCorrectedAzimuth) {
  // The paper prints atan(d_y/d_z); the azimuth is atan2(d_y, d_x).
  const Sensor sensor(Vector3(0.0, 0.0, 0.0));
  const Vector3 z = sensor.measure_position(Vector3(-3.0, -4.0, 12.0));
  EXPECT_DOUBLE_EQ(z(Sensor::kRange), 13.0);
  EXPECT_DOUBLE_EQ(z(Sensor::kAzimuth), std::atan2(-4.0, -3.0));
  EXPECT_DOUBLE_EQ(z(Sensor::kElevation), std::asin(12.0 / 13.0));
}

TEST(RangeAzimuthElevation, ResidualWrapsAzimuthOnly) {
  const Vector3 z(100.0, std::numbers::pi - 0.01, 0.2);
  const Vector3 z_pred(99.0, -std::numbers::pi + 0.01, 0.1);
  const Vector3 nu = Sensor::residual(z, z_pred);
  EXPECT_DOUBLE_EQ(nu(0), 1.0);
  EXPECT_NEAR(nu(1), -0.02, 1e-12);
  EXPECT_NEAR(nu(2), 0.1, 1e-15);
}

TEST(RangeAzimuthElevation, DirectlyOverheadHasNoAzimuthRowInsteadOfInfinity) {
  const Sensor sensor(Vector3(5.0, 5.0, 0.0));
  Vector<9> x = Vector<9>::Zero();
  x.head<3>() = Vector3(5.0, 5.0, 300.0);
  const Jacobian<3, 9> h = sensor.jacobian(x);
  EXPECT_TRUE(h.allFinite());
  EXPECT_EQ(h.row(Sensor::kAzimuth).norm(), 0.0);
  EXPECT_DOUBLE_EQ(h(Sensor::kRange, 2), 1.0);
}

}  // namespace
}  // namespace skyfuse
