#include "skyfuse/traffic/sensor_bias.hpp"

#include <gtest/gtest.h>

#include "skyfuse/models/position_velocity.hpp"
#include "skyfuse/models/range_azimuth.hpp"
#include "skyfuse/models/range_azimuth_altitude.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/scenario/truth.hpp"

namespace skyfuse {
namespace {

constexpr SensorBias kBias{.range_m = 150.0, .azimuth_rad = 0.0026, .elevation_rad = 0.0017};

TEST(SensorBias, OffsetsEachComponentItNamesAndNothingElse) {
  EXPECT_EQ(offsets_of<RangeAzimuthElevation<kKinematicsDim>>(kBias),
            Vector3(150.0, 0.0026, 0.0017));
  EXPECT_EQ(offsets_of<RangeAzimuth<kKinematicsDim>>(kBias), Vector<2>(150.0, 0.0026));
  // A Mode S radar's altitude is the aircraft's own: no elevation to offset.
  EXPECT_EQ(offsets_of<RangeAzimuthAltitude<kKinematicsDim>>(kBias), Vector3(150.0, 0.0026, 0.0));
  EXPECT_EQ(offsets_of<PositionVelocity<kKinematicsDim>>(kBias), Vector<6>::Zero());
  EXPECT_TRUE(kBias.any());
  EXPECT_FALSE(SensorBias{}.any());
  EXPECT_TRUE(SensorBias{.time_s = -0.2}.any());
}

TEST(SensorBias, AClockOffsetMovesTheAircraftAlongItsKinematics) {
  Vector<kKinematicsDim> x;
  x << 1000.0, -200.0, 300.0, 40.0, 10.0, -2.0, 0.5, -1.0, 0.0;
  const Vector<kKinematicsDim> later = kinematics_after(x, 2.0);
  EXPECT_EQ(later.head<3>(), Vector3(1000.0 + 80.0 + 1.0, -200.0 + 20.0 - 2.0, 300.0 - 4.0));
  EXPECT_EQ(later.segment<3>(3), Vector3(41.0, 8.0, -2.0));
  EXPECT_EQ(later.tail<3>(), x.tail<3>());
  EXPECT_EQ(kinematics_after(x, 0.0), x);
}

}  // namespace
}  // namespace skyfuse
