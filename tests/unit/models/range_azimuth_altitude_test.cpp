#include "skyfuse/models/range_azimuth_altitude.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "support/numerical_jacobian.hpp"
#include "support/random_problems.hpp"

namespace skyfuse {
namespace {

using Sensor = RangeAzimuthAltitude<9>;

TEST(RangeAzimuthAltitude, JacobianMatchesFiniteDifferencesAtRandomPoints) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 500; ++trial) {
    const Sensor sensor(test::random_vector3(rng, -2000.0, 2000.0));
    Vector<9> x;
    x << sensor.site() + test::random_vector3(rng, -3000.0, 3000.0),
        test::random_vector3(rng, -80.0, 80.0), test::random_vector3(rng, -5.0, 5.0);
    const Jacobian<3, 9> analytic = sensor.jacobian(x);
    const Jacobian<3, 9> numeric = test::numerical_jacobian(sensor, x);
    for (int row = 0; row < 3; ++row) {
      EXPECT_LE(test::relative_error(analytic.row(row), numeric.row(row)), 1e-6)
          << "row " << row << " at x = " << x.transpose();
    }
  }
}

TEST(RangeAzimuthAltitude, MeasuresSlantRangeAzimuthAndTheAircraftsOwnAltitude) {
  const Sensor sensor(Vector3(10.0, 20.0, 30.0));
  const Vector3 z = sensor.measure_position(Vector3(13.0, 24.0, 42.0));
  EXPECT_DOUBLE_EQ(z(Sensor::kRange), 13.0);  // (3, 4, 12)
  EXPECT_DOUBLE_EQ(z(Sensor::kAzimuth), std::atan2(4.0, 3.0));
  EXPECT_DOUBLE_EQ(z(Sensor::kAltitude), 42.0) << "the frame's height, not the station's";
}

TEST(RangeAzimuthAltitude, OneReplyFixesThePositionItCameFrom) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 200; ++trial) {
    const Sensor sensor(test::random_vector3(rng, -2000.0, 2000.0));
    const Vector3 p = sensor.site() + test::random_vector3(rng, -8000.0, 8000.0);
    EXPECT_LE((sensor.position_of(sensor.measure_position(p)) - p).norm(), 1e-6 * (1.0 + p.norm()))
        << "trial " << trial;
  }
  // A range shorter than the height difference: straight above the station.
  const Sensor sensor(Vector3(1.0, 2.0, 0.0));
  EXPECT_EQ(sensor.position_of(Vector3(90.0, 0.3, 100.0)), Vector3(1.0, 2.0, 100.0));
}

TEST(RangeAzimuthAltitude, ReportsTheAltitudeInStepsOf25Feet) {
  const double step = 25.0 * 0.3048;
  EXPECT_DOUBLE_EQ(Sensor::kAltitudeStepM, step);
  const Vector3 reported = Sensor::to_reported(Vector3(5000.0, std::numbers::pi + 0.25, 318.0));
  EXPECT_DOUBLE_EQ(reported(Sensor::kAltitude), 42.0 * step);  // 318 m is 41.7 steps
  EXPECT_NEAR(reported(Sensor::kAzimuth), -std::numbers::pi + 0.25, 1e-12);
  EXPECT_DOUBLE_EQ(Sensor::to_reported(Vector3(5000.0, 0.0, -3.0))(Sensor::kAltitude), 0.0);
}

TEST(RangeAzimuthAltitude, RefusesWhatNoRadarReports) {
  EXPECT_EQ(Sensor::check_reported(Vector3(100.0, 0.5, 300.0)), std::nullopt);
  EXPECT_EQ(Sensor::check_reported(Vector3(-1.0, 0.5, 300.0)), DropKind::kOutOfRange);
  EXPECT_EQ(Sensor::check_reported(Vector3(100.0, 4.0, 300.0)), DropKind::kOutOfRange);
  EXPECT_EQ(Sensor::check_reported(Vector3(100.0, 0.5, std::nan(""))), DropKind::kNonFinite);
}

TEST(RangeAzimuthAltitude, DirectlyOverheadHasNoAzimuthRowInsteadOfInfinity) {
  const Sensor sensor(Vector3(5.0, 5.0, 0.0));
  Vector<9> x = Vector<9>::Zero();
  x.head<3>() = Vector3(5.0, 5.0, 300.0);
  const Jacobian<3, 9> h = sensor.jacobian(x);
  EXPECT_TRUE(h.allFinite());
  EXPECT_EQ(h.row(Sensor::kAzimuth).norm(), 0.0);
  EXPECT_DOUBLE_EQ(h(Sensor::kAltitude, 2), 1.0);
}

}  // namespace
}  // namespace skyfuse
