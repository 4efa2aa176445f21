#include "skyfuse/registration/station_bias.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <stdexcept>

#include "skyfuse/models/range_azimuth.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/scenario/truth.hpp"

namespace skyfuse {
namespace {

constexpr int N = kKinematicsDim;
using Radar = RangeAzimuthElevation<N>;

const Vector3 kSite(-20000.0, -15000.0, 50.0);
constexpr SensorBias kTrueBias{
    .range_m = 150.0, .azimuth_rad = 0.002618, .elevation_rad = 0.001745, .time_s = 0.5};
constexpr SensorBias kPriorStd{
    .range_m = 500.0, .azimuth_rad = 0.01, .elevation_rad = 0.01, .time_s = 5.0};

GaussianState<N> known_track(int i) {
  GaussianState<N> track;
  const double bearing = 0.37 * i;
  const double range = 15000.0 + 700.0 * (i % 50);
  track.mean.head<3>() = kSite + Vector3(range * std::cos(bearing), range * std::sin(bearing),
                                         1000.0 + 90.0 * (i % 40));
  track.mean.segment<3>(3) << 200.0 * std::cos(1.3 * i), 200.0 * std::sin(1.3 * i), 0.0;
  track.covariance = Covariance<N>::Identity();
  return track;
}

DetectionNoise radar_noise() {
  Covariance<3> r = Covariance<3>::Zero();
  r.diagonal() << 30.0 * 30.0, 0.00087 * 0.00087, 0.0017 * 0.0017;
  return DetectionNoise(r);
}

// What the biased radar reports of the aircraft, without noise.
Detection biased(const Radar& radar, const Vector<N>& x) {
  return Detection(radar.predict(kinematics_after(x, kTrueBias.time_s)) +
                   offsets_of<Radar>(kTrueBias));
}

TEST(StationBias, CorrectsNothingUntilItHasSettledWhatItLearnt) {
  const PictureSensor<N> sensor = Radar(kSite);
  StationBias<N> station(sensor, kPriorStd);
  const GaussianState<N> track = known_track(3);
  const Detection z = biased(std::get<Radar>(sensor), track.mean);
  EXPECT_FALSE(station.bias().any());
  EXPECT_TRUE(station.learn(sensor, track, z, radar_noise()));
  EXPECT_FALSE(station.bias().any()) << "learning alone moves no correction";
  EXPECT_EQ(station.corrected(sensor, z, track.mean), Detection(Radar::to_reported(z)));
  ASSERT_TRUE(station.settle());
  EXPECT_TRUE(station.bias().any());
}

// Noiseless detections of 300 well-known tracks: the settled estimate is the radar's biases,
// and a detection corrected by it is where the aircraft is, the clock's part included.
TEST(StationBias, LearnsARadarsBiasesAndCorrectsItsDetections) {
  const PictureSensor<N> sensor = Radar(kSite);
  const Radar& radar = std::get<Radar>(sensor);
  StationBias<N> station(sensor, kPriorStd);
  for (int i = 0; i < 300; ++i) {
    const GaussianState<N> track = known_track(i);
    ASSERT_TRUE(station.learn(sensor, track, biased(radar, track.mean), radar_noise()));
  }
  ASSERT_TRUE(station.settle());
  EXPECT_NEAR(station.bias().range_m, kTrueBias.range_m, 0.5);
  EXPECT_NEAR(station.bias().azimuth_rad, kTrueBias.azimuth_rad, 1e-5);
  EXPECT_NEAR(station.bias().elevation_rad, kTrueBias.elevation_rad, 1e-5);
  EXPECT_NEAR(station.bias().time_s, kTrueBias.time_s, 0.01);

  // The clock's part is corrected to first order: 0.5 s at 200 m/s moves an aircraft 15 km out
  // by 100 m, whose second-order part in an angle is up to (100 / 15 000)^2 / 2 = 2.2e-5 rad
  // (0.3 m there), a hundredth of the 0.15 deg offset corrected.
  for (int i = 300; i < 320; ++i) {
    const Vector<N> x = known_track(i).mean;
    const Detection corrected = station.corrected(sensor, biased(radar, x), x);
    const Vector3 truth = radar.predict(x);
    EXPECT_NEAR(corrected(0), truth(0), 1.0) << "aircraft " << i;
    EXPECT_NEAR(corrected(1), truth(1), 5e-5) << "aircraft " << i;
    EXPECT_NEAR(corrected(2), truth(2), 5e-5) << "aircraft " << i;
    // In metres at the aircraft: the biases moved it by more than 50 m; corrected, under 2 m.
    const auto metres = [&](const Detection& z) {
      return Vector3(z(0) - truth(0), truth(0) * (z(1) - truth(1)), truth(0) * (z(2) - truth(2)))
          .norm();
    };
    EXPECT_GT(metres(biased(radar, x)), 50.0) << "aircraft " << i;
    EXPECT_LT(metres(corrected), 2.0) << "aircraft " << i;
  }
}

// Without a track, only the offsets come off: a 2-D radar's range and azimuth.
TEST(StationBias, WithoutATrackOnlyTheOffsetsComeOff) {
  using Radar2d = RangeAzimuth<N>;
  const PictureSensor<N> sensor = Radar2d(kSite, HeightBand{0.0, 3000.0});
  StationBias<N> station(sensor, kPriorStd);
  const GaussianState<N> track = known_track(5);
  const Radar2d& radar = std::get<Radar2d>(sensor);
  for (int i = 0; i < 200; ++i) {
    const GaussianState<N> each = known_track(i);
    const Detection z(radar.predict(each.mean) + offsets_of<Radar2d>(kTrueBias));
    Covariance<2> r = Covariance<2>::Zero();
    r.diagonal() << 900.0, 0.00087 * 0.00087;
    ASSERT_TRUE(station.learn(sensor, each, z, DetectionNoise(r)));
  }
  ASSERT_TRUE(station.settle());
  EXPECT_EQ(station.bias().elevation_rad, 0.0) << "a 2-D radar has no elevation to offset";
  const Detection z(radar.predict(track.mean) + offsets_of<Radar2d>(kTrueBias));
  const Detection removed = station.offsets_removed(sensor, z);
  EXPECT_NEAR(removed(0), radar.predict(track.mean)(0), 0.5);
  EXPECT_NEAR(removed(1), radar.predict(track.mean)(1), 1e-5);
}

// What the corrections do not know yet, as R's addition: the prior's until it settles, then the
// estimate's, which learning shrinks.
TEST(StationBias, ItsUncertaintyIsThePriorsUntilItLearns) {
  const PictureSensor<N> sensor = Radar(kSite);
  const Radar& radar = std::get<Radar>(sensor);
  StationBias<N> station(sensor, kPriorStd);
  EXPECT_EQ(station.estimated(), (std::array<bool, 4>{true, true, true, true}));
  EXPECT_EQ(station.sigma().range_m, kPriorStd.range_m);
  EXPECT_EQ(station.sigma().time_s, kPriorStd.time_s);
  EXPECT_EQ(station.clock_variance(), kPriorStd.time_s * kPriorStd.time_s);
  const Covariance<3> offsets = fixed_noise<3>(station.offsets_noise(sensor));
  EXPECT_EQ(offsets, Covariance<3>(Vector3(500.0 * 500.0, 0.01 * 0.01, 0.01 * 0.01).asDiagonal()));
  // G Σ Gᵀ: the offsets' and the clock's, whose column is the aircraft's motion as the radar
  // measures it.
  const GaussianState<N> track = known_track(7);
  const Vector3 clock_column = radar.jacobian(track.mean).leftCols<3>() * track.mean.segment<3>(3);
  const Covariance<3> expected =
      offsets + kPriorStd.time_s * kPriorStd.time_s * clock_column * clock_column.transpose();
  const Covariance<3> considered = fixed_noise<3>(station.correction_noise(sensor, track.mean));
  EXPECT_LT((considered - expected).norm(), 1e-12 * expected.norm());

  for (int i = 0; i < 300; ++i) {
    const GaussianState<N> each = known_track(i);
    ASSERT_TRUE(station.learn(sensor, each, biased(radar, each.mean), radar_noise()));
  }
  ASSERT_TRUE(station.settle());
  EXPECT_LT(station.sigma().range_m, 0.1 * kPriorStd.range_m);
  EXPECT_LT(station.sigma().azimuth_rad, 0.1 * kPriorStd.azimuth_rad);
  EXPECT_LT(fixed_noise<3>(station.correction_noise(sensor, track.mean)).trace(),
            0.01 * considered.trace());
}

TEST(StationBias, A2dRadarEstimatesNoElevation) {
  using Radar2d = RangeAzimuth<N>;
  const StationBias<N> station(PictureSensor<N>(Radar2d(kSite, HeightBand{0.0, 3000.0})),
                               kPriorStd);
  EXPECT_EQ(station.estimated(), (std::array<bool, 4>{true, true, false, true}));
  EXPECT_EQ(station.sigma().elevation_rad, 0.0);
}

// Another node holds the same estimate from its sums alone; sums of another sensor are refused.
TEST(StationBias, AnotherNodeHoldsTheSameEstimateFromItsSums) {
  const PictureSensor<N> sensor = Radar(kSite);
  const Radar& radar = std::get<Radar>(sensor);
  StationBias<N> station(sensor, kPriorStd);
  for (int i = 0; i < 40; ++i) {
    const GaussianState<N> each = known_track(i);
    ASSERT_TRUE(station.learn(sensor, each, biased(radar, each.mean), radar_noise()));
  }
  ASSERT_TRUE(station.settle());
  const BiasSums sums = station.sums(7);
  EXPECT_EQ(sums.station_id, 7);
  EXPECT_EQ(sums.detections, 40U);
  StationBias<N> other(sensor, kPriorStd);
  ASSERT_TRUE(other.restore(sums));
  const Vector<4> mine = BiasEstimate<Radar>::from_sensor_bias(station.bias());
  EXPECT_EQ(BiasEstimate<Radar>::from_sensor_bias(other.bias()), mine);
  EXPECT_EQ(BiasEstimate<Radar>::from_sensor_bias(other.sigma()),
            BiasEstimate<Radar>::from_sensor_bias(station.sigma()));

  using Radar2d = RangeAzimuth<N>;
  StationBias<N> two_d(PictureSensor<N>(Radar2d(kSite, HeightBand{0.0, 3000.0})), kPriorStd);
  EXPECT_FALSE(two_d.restore(sums)) << "a 3-D radar's four entries are not a 2-D radar's three";
  EXPECT_FALSE(two_d.bias().any());
}

TEST(StationBias, RefusesAPriorWithoutSpread) {
  const PictureSensor<N> sensor = Radar(kSite);
  SensorBias none = kPriorStd;
  none.time_s = 0.0;
  EXPECT_THROW(StationBias<N>(sensor, none), std::invalid_argument);
}

}  // namespace
}  // namespace skyfuse
