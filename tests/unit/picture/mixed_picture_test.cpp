// A picture whose stations carry different sensors: a radar (range, azimuth, elevation) and a
// position-velocity report (what an aircraft broadcasting ADS-B gives a ground station). Each
// station's detections are of its own sensor's size and gated by its own chi-square; a peer per
// station, each assigning only its own scan, holds the same picture as the other bit for bit,
// and the center, which stacks both sensors' detections of a track at once, agrees.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <utility>
#include <variant>
#include <vector>

#include "skyfuse/metrics/chi_square.hpp"
#include "skyfuse/models/constant_velocity.hpp"
#include "skyfuse/models/position_velocity.hpp"
#include "skyfuse/models/range_azimuth.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/picture/central_picture.hpp"
#include "skyfuse/picture/peer_picture.hpp"
#include "skyfuse/picture/picture_sensor.hpp"
#include "skyfuse/picture/track_filters.hpp"
#include "skyfuse/registry/make_parts.hpp"
#include "skyfuse/tracking/ekf_increment_rule.hpp"
#include "skyfuse/traffic/scan_simulation.hpp"
#include "unit/picture/picture_round.hpp"

namespace skyfuse {
namespace {

using Model = ConstantVelocity3D;
constexpr int N = Model::kDim;
using Radar = RangeAzimuthElevation<N>;
using Broadcast = PositionVelocity<N>;
using Radar2d = RangeAzimuth<N>;
using PeerTracks = PeerModelTracks<Model, EkfIncrementRule>;
using Peer = PeerPicture<PeerTracks>;
using Center = CentralPicture<CenterStackedTracks<Model>>;
using Station = KnownStation<N>;

constexpr double kTimeStepS = 1.0;
constexpr std::uint64_t kSeed = 4242;
constexpr int kRounds = 30;

// Station 1: a radar south-west of the aircraft; station 2: the aircraft's own reports.
std::vector<Station> mixed_stations() {
  const double angle_std = 0.2 * std::numbers::pi / 180.0;
  Covariance<3> radar_noise = Covariance<3>::Zero();
  radar_noise.diagonal() << 5.0 * 5.0, angle_std * angle_std, angle_std * angle_std;
  Covariance<6> broadcast_noise = Covariance<6>::Zero();
  broadcast_noise.diagonal() << 100.0, 100.0, 100.0, 1.0, 1.0, 1.0;
  return {{1, Radar(Vector3(-3000.0, -2000.0, 30.0)), radar_noise, 1.0, {}},
          {2, Broadcast(), broadcast_noise, 1.0, {}}};
}

// One aircraft flying straight and level-ish for the whole run.
std::vector<TargetTruth> one_aircraft() {
  TargetTruth truth{"T0", 0, {}};
  const Vector3 start(-1500.0, 800.0, 350.0);
  const Vector3 velocity(35.0, -10.0, 0.5);
  for (int k = 0; k < kRounds; ++k) {
    Vector<kKinematicsDim> x = Vector<kKinematicsDim>::Zero();
    x.head<3>() = start + k * kTimeStepS * velocity;
    x.segment<3>(3) = velocity;
    truth.states.push_back(x);
  }
  return {truth};
}

// Relative gap of two matrices, as in_process_network_test.cpp measures the center's.
template <typename A, typename B>
double relative_gap(const A& mine, const B& theirs) {
  return (mine - theirs).norm() / (1.0 + theirs.norm());
}

// What kRounds rounds of a picture showed: the center's worst relative gap to the peers, and how
// many track-rounds every station's detection updated.
struct Played {
  double worst_gap = 0.0;
  int updated_by_every_station = 0;
};

// Plays kRounds rounds of `stations` (a peer each, and the center) over `truths`, holding every
// peer to the same bits as the first, the center to the peers' associations and tracks, and
// each detection to its sensor's size, every round.
void play_and_check(const std::vector<Station>& stations, const std::vector<TargetTruth>& truths,
                    const DetectionConfig& sees, std::vector<Peer>& peers, Center& center,
                    Played& played) {
  std::vector<int> every_station;
  for (const Station& station : stations) every_station.push_back(station.id);
  for (int k = 0; k < kRounds; ++k) {
    const auto step = static_cast<std::uint64_t>(k);
    std::vector<Scan> scans;
    for (const Station& station : stations) {
      scans.push_back(simulate_scan(station.id, test::truth_sensor_of(station),
                                    test::site_of(station), station.noise, sees, truths, k, kSeed,
                                    0));
      for (const Detection& z : scans.back().detections) {
        ASSERT_EQ(z.size(), measurement_dim<N>(station.sensor)) << "station " << station.id;
      }
    }
    const std::vector<Peer::Report> reports = test::play_picture_round(
        step, peers, center, std::span<const Station>(stations), std::span<const Scan>(scans));

    for (std::size_t p = 1; p < peers.size(); ++p) {
      ASSERT_EQ(peers[0].digest(), peers[p].digest()) << "round " << k << ", peer " << p;
    }
    std::vector<Association> peer_associations;
    for (const auto& report : reports) {
      for (const ReportedPair& pair : report.pairs) {
        peer_associations.push_back({report.station_id, pair.detection, pair.track});
      }
    }
    ASSERT_EQ(peer_associations, center.associations()) << "round " << k;
    ASSERT_EQ(peers[0].tracks().size(), center.tracks().size()) << "round " << k;
    for (std::size_t t = 0; t < center.tracks().size(); ++t) {
      const auto& mine = peers[0].tracks()[t];
      const auto& theirs = center.tracks()[t];
      ASSERT_EQ(mine.id, theirs.id) << "round " << k;
      EXPECT_EQ(mine.updated_by, theirs.updated_by) << "round " << k;
      played.worst_gap =
          std::max(played.worst_gap, relative_gap(mine.filter.mean, theirs.filter.mean));
      played.worst_gap = std::max(played.worst_gap,
                                  relative_gap(mine.filter.covariance, theirs.filter.covariance));
      if (mine.updated_by == every_station) ++played.updated_by_every_station;
    }
  }
}

// A peer per station and the center, empty, with the tests' motion model and tracker
// (`relinearisations`: its updater's).
std::pair<std::vector<Peer>, Center> empty_network(const std::vector<Station>& stations,
                                                   int relinearisations = 0) {
  const Model motion(kTimeStepS, {0.5, 1.0});
  const Vector<N> initial_variance = Vector<N>::Constant(100.0);
  TrackerConfig config;
  config.updater.relinearisations = relinearisations;
  return {std::vector<Peer>(
              stations.size(),
              Peer(PeerTracks(motion, initial_variance, relinearisations), stations, config)),
          Center(CenterStackedTracks<Model>(motion, initial_variance, relinearisations), stations,
                 config)};
}

// The confirmed tracks at the end: one, on the aircraft, within `within_m`.
void expect_one_confirmed_track_on(const Peer& peer, const TargetTruth& aircraft, double within_m) {
  const Vector<kKinematicsDim>& truth = aircraft.states.back();
  std::size_t confirmed = 0;
  for (const auto& track : peer.tracks()) {
    if (track.status != TrackStatus::kConfirmed) continue;
    ++confirmed;
    EXPECT_LT((track.filter.mean.head<3>() - truth.head<3>()).norm(), within_m);
    EXPECT_LT((track.filter.mean.segment<3>(3) - truth.segment<3>(3)).norm(), 5.0);
  }
  EXPECT_EQ(confirmed, 1U);
}

TEST(MixedPicture, ARadarAndAPositionVelocityStationShareOnePicture) {
  const std::vector<TargetTruth> truths = one_aircraft();
  const std::vector<Station> stations = mixed_stations();
  ASSERT_EQ(measurement_dim<N>(stations[0].sensor), 3);
  ASSERT_EQ(measurement_dim<N>(stations[1].sensor), 6);
  auto [peers, center] = empty_network(stations);
  DetectionConfig sees;
  sees.field_of_view.max_range_m = 20000.0;
  sees.field_of_view.min_elevation_rad = 0.0;
  sees.clutter_per_scan = 2.0;

  Played played;
  play_and_check(stations, truths, sees, peers, center, played);
  EXPECT_LT(played.worst_gap, 1e-9);
  // The center's update stacked a radar's and a position-velocity detection of one track.
  EXPECT_GT(played.updated_by_every_station, kRounds / 2);
  // After the last round: the aircraft, and nothing else, has a confirmed track, close to it.
  expect_one_confirmed_track_on(peers[0], truths.front(), 50.0);
}

// A tracker that relinearises each detection's increment (fusion/relinearised_increment.hpp):
// the peers still hold one picture and the center, which then fuses per-detection increments
// instead of one stacked update, stays within 1e-9 of them; and the tracks are not the ones
// linearised at the prior.
TEST(MixedPicture, ARelinearisingTrackerKeepsItsPeersAndCenterTogether) {
  const std::vector<TargetTruth> truths = one_aircraft();
  const std::vector<Station> stations = mixed_stations();
  DetectionConfig sees;
  sees.field_of_view.max_range_m = 20000.0;
  sees.field_of_view.min_elevation_rad = 0.0;
  sees.clutter_per_scan = 2.0;
  auto [peers, center] = empty_network(stations, 2);
  Played played;
  play_and_check(stations, truths, sees, peers, center, played);
  EXPECT_LT(played.worst_gap, 1e-9);
  EXPECT_GT(played.updated_by_every_station, kRounds / 2);
  expect_one_confirmed_track_on(peers[0], truths.front(), 50.0);

  auto [at_prior, at_prior_center] = empty_network(stations);
  Played at_prior_played;
  play_and_check(stations, truths, sees, at_prior, at_prior_center, at_prior_played);
  ASSERT_EQ(peers[0].tracks().size(), at_prior[0].tracks().size());
  double moved = 0.0;
  for (std::size_t t = 0; t < peers[0].tracks().size(); ++t) {
    moved = std::max(
        moved,
        (peers[0].tracks()[t].filter.mean - at_prior[0].tracks()[t].filter.mean).head<3>().norm());
  }
  EXPECT_GT(moved, 1e-6) << "the relinearised tracks are the prior-linearised ones";
}

// Two 2-D radars (range and azimuth, no height) and a 3-D radar: the 2-D radars' detections
// place the aircraft at their height band's middle (300 m) and join the 3-D radar's when the
// track starts; the track flies at the aircraft's height (420 m), which only the 3-D radar and
// the slant ranges tell; peers hold one picture bit for bit and the center agrees.
TEST(MixedPicture, TwoDimensionalRadarsShareAPictureWithA3dRadar) {
  const HeightBand band{100.0, 500.0};
  const double angle_std = 0.2 * std::numbers::pi / 180.0;
  Covariance<3> radar_noise = Covariance<3>::Zero();
  radar_noise.diagonal() << 5.0 * 5.0, angle_std * angle_std, angle_std * angle_std;
  Covariance<2> radar_2d_noise = Covariance<2>::Zero();
  radar_2d_noise.diagonal() << 10.0 * 10.0, angle_std * angle_std;
  const std::vector<Station> stations = {
      {1, Radar2d(Vector3(-3000.0, -2000.0, 30.0), band), radar_2d_noise, 1.0, {}},
      {2, Radar2d(Vector3(4000.0, 3000.0, 20.0), band), radar_2d_noise, 1.0, {}},
      {3, Radar(Vector3(0.0, -5000.0, 25.0)), radar_noise, 1.0, {}}};
  ASSERT_EQ(measurement_dim<N>(stations[0].sensor), 2);

  std::vector<TargetTruth> truths = one_aircraft();
  for (auto& x : truths.front().states) x(2) += 70.0;  // 420 m and climbing slowly
  auto [peers, center] = empty_network(stations);
  DetectionConfig sees;
  sees.field_of_view.max_range_m = 20000.0;
  sees.clutter_per_scan = 2.0;

  Played played;
  play_and_check(stations, truths, sees, peers, center, played);
  EXPECT_LT(played.worst_gap, 1e-9);
  EXPECT_GT(played.updated_by_every_station, kRounds / 2);
  expect_one_confirmed_track_on(peers[0], truths.front(), 30.0);
  for (const auto& track : peers[0].tracks()) {
    if (track.status != TrackStatus::kConfirmed) continue;
    EXPECT_LT(std::abs(track.filter.mean(2) - truths.front().states.back()(2)), 20.0)
        << "not the band's 300 m";
  }
}

// Two 2-D radars alone: nothing measures the aircraft's height, so every node bounds it by the
// band the radars assume (picture/height_bound.hpp). Every track's height variance ends each
// round at most the band's, the peers hold one picture and the center stays within 1e-9.
TEST(MixedPicture, TwoDimensionalRadarsAloneKeepTheirTracksHeightWithinTheBand) {
  const HeightBand band{330.0, 390.0};  // σ 17 m: less than the slant ranges tell
  const double angle_std = 0.2 * std::numbers::pi / 180.0;
  Covariance<2> radar_2d_noise = Covariance<2>::Zero();
  radar_2d_noise.diagonal() << 10.0 * 10.0, angle_std * angle_std;
  const std::vector<Station> stations = {
      {1, Radar2d(Vector3(-3000.0, -2000.0, 30.0), band), radar_2d_noise, 1.0, {}},
      {2, Radar2d(Vector3(4000.0, 3000.0, 20.0), band), radar_2d_noise, 1.0, {}}};
  const std::vector<TargetTruth> truths = one_aircraft();
  auto [peers, center] = empty_network(stations);
  DetectionConfig sees;
  sees.field_of_view.max_range_m = 20000.0;

  Played played;
  play_and_check(stations, truths, sees, peers, center, played);
  EXPECT_LT(played.worst_gap, 1e-9);
  ASSERT_FALSE(peers[0].tracks().empty());
  for (const auto& track : peers[0].tracks()) {
    EXPECT_LE(track.filter.covariance(2, 2), band.variance_m2() * (1.0 + 1e-12)) << track.id;
    // The bound held it: the radars' slant ranges alone leave more.
    EXPECT_NEAR(track.filter.covariance(2, 2), band.variance_m2(), 1e-9 * band.variance_m2());
  }
  for (const auto& track : center.tracks()) {
    EXPECT_LE(track.filter.covariance(2, 2), band.variance_m2() * (1.0 + 1e-12)) << track.id;
  }
}

TEST(MixedPicture, EachStationIsGatedByItsOwnMeasurementDimension) {
  const std::vector<Station> stations = mixed_stations();
  TrackerConfig config;
  config.association.gate_probability = 0.999;
  const Peer peer(PeerTracks(Model(kTimeStepS, {0.5, 1.0}), Vector<N>::Constant(100.0)), stations,
                  config);
  EXPECT_EQ(peer.gate(3), chi_square_quantile(0.999, 3));
  EXPECT_EQ(peer.gate(6), chi_square_quantile(0.999, 6));
  EXPECT_NE(peer.gate(3), peer.gate(6));

  // The gate each station's association used is its own sensor's.
  const std::vector<TargetTruth> truths = one_aircraft();
  AssociationWork work;
  for (const Station& station : stations) {
    const Scan scan =
        simulate_scan(station.id, test::truth_sensor_of(station), test::site_of(station),
                      station.noise, DetectionConfig{}, truths, 0, kSeed, 0);
    peer.associate(station, scan, work);
    const int m = measurement_dim<N>(station.sensor);
    EXPECT_EQ(work.hypotheses.gate, chi_square_quantile(0.999, m)) << "station " << station.id;
    EXPECT_EQ(work.hypotheses.detections, 1U) << "station " << station.id;
  }
}

}  // namespace
}  // namespace skyfuse
