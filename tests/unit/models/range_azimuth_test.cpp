#include "skyfuse/models/range_azimuth.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "skyfuse/picture/initiation.hpp"
#include "support/numerical_jacobian.hpp"
#include "support/random_problems.hpp"

namespace skyfuse {
namespace {

using Sensor = RangeAzimuth<9>;
const HeightBand kBand{100.0, 500.0};

TEST(RangeAzimuth, JacobianMatchesFiniteDifferencesAtRandomPoints) {
  std::mt19937 rng(13);
  for (int trial = 0; trial < 500; ++trial) {
    const Sensor sensor(test::random_vector3(rng, -2000.0, 2000.0), kBand);
    Vector<9> x;
    x << sensor.site() + test::random_vector3(rng, -3000.0, 3000.0),
        test::random_vector3(rng, -80.0, 80.0), test::random_vector3(rng, -5.0, 5.0);
    const Jacobian<2, 9> analytic = sensor.jacobian(x);
    const Jacobian<2, 9> numeric = test::numerical_jacobian(sensor, x);
    for (int row = 0; row < 2; ++row) {
      EXPECT_LE(test::relative_error(analytic.row(row), numeric.row(row)), 1e-6)
          << "row " << row << " at x = " << x.transpose();
    }
  }
}

TEST(RangeAzimuth, MeasuresSlantRangeAndAzimuthOnly) {
  const Sensor sensor(Vector3(10.0, 20.0, 30.0), kBand);
  const Vector<2> z = sensor.measure_position(Vector3(13.0, 24.0, 42.0));
  EXPECT_DOUBLE_EQ(z(Sensor::kRange), 13.0);  // (3, 4, 12)
  EXPECT_DOUBLE_EQ(z(Sensor::kAzimuth), std::atan2(4.0, 3.0));
}

TEST(RangeAzimuth, PlacesAnEchoOnItsRangeCircleAtTheBandsMiddle) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    const Sensor sensor(
        Vector3(0.0, 0.0, 20.0) +
            test::random_vector3(rng, -2000.0, 2000.0).cwiseProduct(Vector3(1.0, 1.0, 0.0)),
        kBand);
    Vector3 p = sensor.site() + test::random_vector3(rng, -8000.0, 8000.0);
    p.z() = kBand.middle_m();
    // An aircraft at the band's middle is placed where it is; one above or below it, on the
    // same range and azimuth at the middle's height.
    EXPECT_LE((sensor.position_of(sensor.measure_position(p)) - p).norm(), 1e-6 * (1.0 + p.norm()))
        << "trial " << trial;
    const Vector3 high(p.x(), p.y(), kBand.high_m);
    const Vector3 placed = sensor.position_of(sensor.measure_position(high));
    EXPECT_DOUBLE_EQ(placed.z(), kBand.middle_m());
    EXPECT_NEAR((placed - sensor.site()).norm(), (high - sensor.site()).norm(), 1e-6);
    EXPECT_NEAR(sensor.measure_position(placed)(Sensor::kAzimuth),
                sensor.measure_position(high)(Sensor::kAzimuth), 1e-12);
  }
  // A range shorter than the height difference: straight above the station.
  const Sensor sensor(Vector3(1.0, 2.0, 0.0), kBand);
  EXPECT_EQ(sensor.position_of(Vector<2>(90.0, 0.3)), Vector3(1.0, 2.0, 300.0));
}

TEST(RangeAzimuth, AFixHoldsTheBandAsItsHeightsSpreadAndTheRadarsNoiseAcrossIt) {
  const Sensor sensor(Vector3::Zero(), kBand);
  const Vector3 p(8000.0, 6000.0, 300.0);  // 10 km out, in the band's middle
  Covariance<2> noise = Covariance<2>::Zero();
  noise.diagonal() << 25.0 * 25.0, 0.002 * 0.002;
  const auto fix = fix_position(3, 1, sensor, sensor.measure_position(p), noise);
  ASSERT_TRUE(fix.has_value());
  EXPECT_LE((fix->position - p).norm(), 1e-6);
  // Along the line of sight the range's 25 m, across it 10 km x 2 mrad = 20 m, and in height
  // the band's (400 m)^2 / 12; the slant range couples height and ground range a little
  // (300 m up at 10 km: 3 %), so each within a few per cent.
  const Vector3 along = Vector3(0.8, 0.6, 0.0);
  const Vector3 across = Vector3(-0.6, 0.8, 0.0);
  EXPECT_NEAR(std::sqrt(along.dot(fix->covariance * along)), 25.0, 0.5);
  EXPECT_NEAR(std::sqrt(across.dot(fix->covariance * across)), 20.0, 1e-6 * 20.0);
  EXPECT_NEAR(fix->covariance(2, 2), kBand.variance_m2(), 0.01 * kBand.variance_m2());
  EXPECT_TRUE((fix->information * fix->covariance).isApprox(Covariance<3>::Identity(), 1e-9));
}

TEST(RangeAzimuth, ATrackStartedWithA3dRadarTakesThe3dRadarsHeight) {
  // A 2-D radar's fix and a 3-D radar's of one aircraft at 420 m, near the band's top: they
  // agree (the band is wide in height), and the track they start is at the 3-D radar's height,
  // not the band's middle.
  const Vector3 p(5000.0, 2000.0, 420.0);
  const Sensor two_d(Vector3(0.0, 0.0, 10.0), kBand);
  const RangeAzimuthElevation<9> three_d(Vector3(9000.0, 0.0, 15.0));
  Covariance<2> noise_2d = Covariance<2>::Zero();
  noise_2d.diagonal() << 20.0 * 20.0, 0.001 * 0.001;
  Covariance<3> noise_3d = Covariance<3>::Zero();
  noise_3d.diagonal() << 5.0 * 5.0, 0.0005 * 0.0005, 0.0005 * 0.0005;
  const std::vector<PositionFix> fixes = {
      *fix_position(1, 0, two_d, two_d.measure_position(p), noise_2d),
      *fix_position(2, 0, three_d, three_d.measure_position(p), noise_3d)};
  InitiationConfig config;
  config.min_stations = 2;
  const std::vector<NewTrack> tracks = initiate_tracks(fixes, 0, config);
  ASSERT_EQ(tracks.size(), 1u);
  EXPECT_EQ(tracks[0].stations, (std::vector<int>{1, 2}));
  EXPECT_NEAR(tracks[0].position.z(), p.z(), 5.0) << "not the band's middle, 300 m";
  EXPECT_NEAR((tracks[0].position - p).norm(), 0.0, 10.0);
}

TEST(RangeAzimuth, RefusesWhatNoRadarReports) {
  EXPECT_EQ(Sensor::check_reported(Vector<2>(100.0, 0.5)), std::nullopt);
  EXPECT_EQ(Sensor::check_reported(Vector<2>(-1.0, 0.5)), DropKind::kOutOfRange);
  EXPECT_EQ(Sensor::check_reported(Vector<2>(100.0, 4.0)), DropKind::kOutOfRange);
  EXPECT_EQ(Sensor::check_reported(Vector<2>(std::nan(""), 0.5)), DropKind::kNonFinite);
  EXPECT_NEAR(Sensor::to_reported(Vector<2>(5000.0, std::numbers::pi + 0.25))(Sensor::kAzimuth),
              -std::numbers::pi + 0.25, 1e-12);
}

TEST(RangeAzimuth, DirectlyOverheadHasNoAzimuthRowInsteadOfInfinity) {
  const Sensor sensor(Vector3(5.0, 5.0, 0.0), kBand);
  Vector<9> x = Vector<9>::Zero();
  x.head<3>() = Vector3(5.0, 5.0, 300.0);
  const Jacobian<2, 9> h = sensor.jacobian(x);
  EXPECT_TRUE(h.allFinite());
  EXPECT_EQ(h.row(Sensor::kAzimuth).norm(), 0.0);
}

}  // namespace
}  // namespace skyfuse
