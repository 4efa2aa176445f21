// The `least_squares` registration as the tracker holds it (picture/registrations/
// least_squares.hpp): chosen by name from the registry, which stations it corrects, and the rule
// that picks what each pair learns against.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "skyfuse/models/position_velocity.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/picture/registration.hpp"
#include "skyfuse/picture/registrations/least_squares.hpp"
#include "skyfuse/scenario/truth.hpp"

namespace skyfuse {
namespace {

constexpr int N = kKinematicsDim;
using Radar = RangeAzimuthElevation<N>;
using Registration = LeastSquaresRegistration<N>;
using Station = KnownStation<N>;

const Vector3 kSite(-20000.0, -15000.0, 50.0);
constexpr SensorBias kTrueBias{
    .range_m = 150.0, .azimuth_rad = 0.002618, .elevation_rad = 0.001745, .time_s = 0.0};

// The part of a track the rule reads: its status and who updated it last round.
struct TrackSeen {
  TrackStatus status = TrackStatus::kConfirmed;
  std::vector<int> updated_by;
};

std::vector<Station> radar_and_reference() {
  Covariance<3> radar_noise = Covariance<3>::Zero();
  radar_noise.diagonal() << 30.0 * 30.0, 0.00087 * 0.00087, 0.0017 * 0.0017;
  const Covariance<6> report_noise = Vector<6>(225, 225, 225, 4, 4, 4).asDiagonal();
  return {{1, Radar(kSite), DetectionNoise(radar_noise), 1.0, {}},
          {4, PositionVelocity<N>(), DetectionNoise(report_noise), 1.0, {}}};
}

RegistrationConfig least_squares() {
  RegistrationConfig config;
  config.kind = "least_squares";
  return config;
}

// Aircraft i's state, spread in range, bearing and height around the radar.
GaussianState<N> aircraft(int i) {
  GaussianState<N> state;
  const double bearing = 0.37 * i;
  const double range = 15000.0 + 700.0 * (i % 50);
  state.mean.head<3>() = kSite + Vector3(range * std::cos(bearing), range * std::sin(bearing),
                                         1000.0 + 90.0 * (i % 40));
  state.mean.segment<3>(3) << 200.0 * std::cos(1.3 * i), 200.0 * std::sin(1.3 * i), 0.0;
  state.covariance = 100.0 * Covariance<N>::Identity();
  return state;
}

TEST(RegistrationRegistry, NamesEveryKindAndWhetherItEstimates) {
  EXPECT_EQ(registration_names(), "none, least_squares");
  ASSERT_NE(find_registration("least_squares"), nullptr);
  EXPECT_TRUE(find_registration("least_squares")->estimates);
  EXPECT_FALSE(find_registration("none")->estimates);
  EXPECT_EQ(find_registration("kalman"), nullptr);
  RegistrationConfig config;
  EXPECT_FALSE(estimates_biases(config)) << "none by default";
  EXPECT_TRUE(estimates_biases(least_squares()));
}

TEST(LeastSquaresRegistration, NoneHoldsNothingAndCorrectsNothing) {
  const std::vector<Station> stations = radar_and_reference();
  const Registration none(RegistrationConfig{}, stations);
  EXPECT_FALSE(none.active());
  EXPECT_FALSE(none.corrects(0));
  EXPECT_TRUE(none.sums(stations).empty());
}

TEST(LeastSquaresRegistration, CorrectsTheRadarNotTheAircraftsOwnReport) {
  const std::vector<Station> stations = radar_and_reference();
  const Registration registration(least_squares(), stations);
  EXPECT_TRUE(registration.active());
  EXPECT_TRUE(registration.corrects(0));
  EXPECT_FALSE(registration.corrects(1));
}

// Every radar pair of a confirmed track learns against the same track's own report of the
// round; a tentative track's, a track without a report's, and the report's own pairs teach
// nothing. Noise-free detections of a biased radar give its offsets back.
TEST(LeastSquaresRegistration, LearnsTheRadarAgainstTheSameTracksReport) {
  const std::vector<Station> stations = radar_and_reference();
  Registration registration(least_squares(), stations);
  const Radar& radar = std::get<Radar>(stations[0].sensor);
  constexpr int kTracks = 40;
  std::vector<TrackSeen> tracks(kTracks);
  std::vector<GaussianState<N>> priors;
  std::vector<Detection> plots;
  std::vector<Detection> reports;
  for (int i = 0; i < kTracks; ++i) {
    const GaussianState<N> truth = aircraft(i);
    priors.push_back(truth);
    plots.emplace_back(radar.predict(truth.mean) + offsets_of<Radar>(kTrueBias));
    reports.emplace_back(truth.mean.head<6>());
  }
  tracks[0].status = TrackStatus::kTentative;
  std::vector<PairedDetection> pairs;
  for (std::size_t t = 0; t < kTracks; ++t) pairs.push_back({0, t, &plots[t]});
  // Every track but the last has its own report this round.
  for (std::size_t t = 0; t + 1 < kTracks; ++t) pairs.push_back({1, t, &reports[t]});

  registration.learn(pairs, tracks, priors, stations);
  const std::vector<BiasSums> sums = registration.sums(stations);
  ASSERT_EQ(sums.size(), 2U);
  EXPECT_EQ(sums[0].detections, kTracks - 2U) << "not the tentative track, not the unreported";
  EXPECT_EQ(sums[1].detections, 0U) << "the reference learns nothing";
  EXPECT_FALSE(registration.of(0).bias().any()) << "nothing corrects before the round settles";

  registration.settle();
  const SensorBias& learnt = registration.of(0).bias();
  EXPECT_NEAR(learnt.range_m, kTrueBias.range_m, 0.5);
  EXPECT_NEAR(learnt.azimuth_rad, kTrueBias.azimuth_rad, 1e-5);
  EXPECT_NEAR(learnt.elevation_rad, kTrueBias.elevation_rad, 1e-5);
  EXPECT_NEAR(learnt.time_s, 0.0, 1e-3);

  // The gate then sees the plots with the offsets removed and their uncertainty added.
  Scan scan{1, stations[0].noise, {plots[5]}};
  Scan gated;
  std::vector<GaussianState<N>> gated_priors;
  registration.gate_inputs(0, stations[0], scan, priors, gated, gated_priors);
  EXPECT_NEAR(gated.detections[0](0), radar.predict(priors[5].mean)(0), 0.5);
  EXPECT_GT(gated.noise(0, 0), stations[0].noise(0, 0));
  EXPECT_GT(gated_priors[5].covariance(0, 0), priors[5].covariance(0, 0)) << "the clock's share";

  // And a restored node holds the same bits.
  Registration other(least_squares(), stations);
  ASSERT_TRUE(other.restore(sums, stations));
  EXPECT_EQ(other.of(0).bias().range_m, learnt.range_m);
  EXPECT_EQ(other.of(0).bias().azimuth_rad, learnt.azimuth_rad);
  EXPECT_EQ(other.of(0).bias().time_s, learnt.time_s);
  EXPECT_FALSE(other.restore(std::vector<BiasSums>(sums.begin(), sums.begin() + 1), stations))
      << "every station's sums or none";
}

// Without a reference a pair learns against the track's prior, and only where another station
// updated the track last round: a track only this radar holds would teach it its own estimate.
TEST(LeastSquaresRegistration, WithoutAReferenceLearnsOnlyFromOthersTracks) {
  std::vector<Station> stations = radar_and_reference();
  stations[1] = {2, Radar(Vector3(22000.0, -10000.0, 80.0)), stations[0].noise, 1.0, {}};
  Registration registration(least_squares(), stations);
  EXPECT_TRUE(registration.corrects(1)) << "two radars: neither is a reference";
  const Radar& radar = std::get<Radar>(stations[0].sensor);
  std::vector<TrackSeen> tracks(2);
  tracks[0].updated_by = {1};
  tracks[1].updated_by = {1, 2};
  const std::vector<GaussianState<N>> priors = {aircraft(1), aircraft(2)};
  const std::vector<Detection> plots = {Detection(radar.predict(priors[0].mean)),
                                        Detection(radar.predict(priors[1].mean))};
  const std::vector<PairedDetection> pairs = {{0, 0, &plots[0]}, {0, 1, &plots[1]}};
  registration.learn(pairs, tracks, priors, stations);
  EXPECT_EQ(registration.sums(stations)[0].detections, 1U);
}

}  // namespace
}  // namespace skyfuse
