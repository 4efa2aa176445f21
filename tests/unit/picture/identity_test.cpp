// Identity (picture/identity.hpp): an aircraft's own address, reported by a cooperative
// sensor, decides which track a detection goes to, joins a primary radar's track and the
// aircraft's broadcast into one, starts a track from one report, and refuses a report that
// claims a track's address from where that aircraft cannot be. Every peer decides it alike, and
// the center with them.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <variant>
#include <vector>

#include "skyfuse/models/constant_velocity.hpp"
#include "skyfuse/models/position_velocity.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/picture/central_picture.hpp"
#include "skyfuse/picture/peer_picture.hpp"
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
using PeerTracks = PeerModelTracks<Model, EkfIncrementRule>;
using Peer = PeerPicture<PeerTracks>;
using Center = CentralPicture<CenterStackedTracks<Model>>;
using Station = KnownStation<N>;

constexpr double kTimeStepS = 1.0;
constexpr std::uint64_t kSeed = 977;
constexpr int kRounds = 30;
constexpr Address kAircraft = 0xABCDEF;

Covariance<3> radar_noise() {
  const double angle_std = 0.2 * std::numbers::pi / 180.0;
  Covariance<3> r = Covariance<3>::Zero();
  r.diagonal() << 5.0 * 5.0, angle_std * angle_std, angle_std * angle_std;
  return r;
}
Covariance<6> broadcast_noise() {
  Covariance<6> r = Covariance<6>::Zero();
  r.diagonal() << 100.0, 100.0, 100.0, 1.0, 1.0, 1.0;
  return r;
}

// Station 1: a primary radar (no addresses); station 2: a receiver of the aircraft's broadcasts.
std::vector<Station> radar_and_receiver() {
  return {{1, Radar(Vector3(-3000.0, -2000.0, 30.0)), radar_noise(), 1.0, {}},
          {2, Broadcast(), broadcast_noise(), 1.0, {}}};
}

TargetTruth straight_aircraft(Address address, const Vector3& start, const Vector3& velocity) {
  TargetTruth truth{"T0", 0, {}};
  truth.address = address;
  for (int k = 0; k < kRounds; ++k) {
    Vector<kKinematicsDim> x = Vector<kKinematicsDim>::Zero();
    x.head<3>() = start + k * kTimeStepS * velocity;
    x.segment<3>(3) = velocity;
    truth.states.push_back(x);
  }
  return truth;
}

TargetTruth the_aircraft() {
  return straight_aircraft(kAircraft, Vector3(-1500.0, 800.0, 350.0), Vector3(35.0, -10.0, 0.5));
}

// What each station senses: the radar everything in range (with clutter), the receiver only
// aircraft that broadcast, with their addresses.
DetectionConfig radar_detection() {
  DetectionConfig d;
  d.field_of_view.max_range_m = 20000.0;
  d.field_of_view.min_elevation_rad = 0.0;
  d.clutter_per_scan = 2.0;
  return d;
}
DetectionConfig receiver_detection() {
  DetectionConfig d;
  d.reports_address = true;
  return d;
}

std::vector<Scan> scans_at(int k, const std::vector<Station>& stations,
                           const std::vector<TargetTruth>& truths) {
  std::vector<Scan> scans;
  for (const Station& station : stations) {
    const DetectionConfig d =
        std::holds_alternative<Radar>(station.sensor) ? radar_detection() : receiver_detection();
    scans.push_back(simulate_scan(station.id, test::truth_sensor_of(station),
                                  test::site_of(station), station.noise, d, truths, k, kSeed, 0));
  }
  return scans;
}

struct Network {
  std::vector<Station> stations;
  std::vector<Peer> peers;
  Center center;

  Network(std::vector<Station> s, const TrackerConfig& config)
      : stations(std::move(s)),
        peers(stations.size(), Peer(PeerTracks(motion(), variance()), stations, config)),
        center(CenterStackedTracks<Model>(motion(), variance()), stations, config) {}
  static Model motion() { return Model(kTimeStepS, {0.5, 1.0}); }
  static Vector<N> variance() { return Vector<N>::Constant(100.0); }

  std::vector<Peer::Report> round(int k, std::span<const Scan> scans) {
    return test::play_picture_round(static_cast<std::uint64_t>(k), peers, center,
                                    std::span<const Station>(stations), scans);
  }
  // Every peer holds the first's picture, addresses included, and the center the same tracks
  // with the same addresses.
  void expect_agreement(int k) const {
    for (const Peer& peer : peers) ASSERT_EQ(peer.digest(), peers[0].digest()) << "round " << k;
    ASSERT_EQ(peers[0].tracks().size(), center.tracks().size()) << "round " << k;
    for (std::size_t t = 0; t < center.tracks().size(); ++t) {
      EXPECT_EQ(peers[0].tracks()[t].id, center.tracks()[t].id) << "round " << k;
      EXPECT_EQ(peers[0].tracks()[t].address, center.tracks()[t].address) << "round " << k;
    }
  }
};

std::size_t confirmed(const Peer& peer) {
  return static_cast<std::size_t>(
      std::count_if(peer.tracks().begin(), peer.tracks().end(),
                    [](const auto& track) { return track.status == TrackStatus::kConfirmed; }));
}

TEST(Identity, ARadarTrackAndTheAircraftsBroadcastAreOneTrackWithItsAddress) {
  const std::vector<TargetTruth> truths = {the_aircraft()};
  Network net(radar_and_receiver(), TrackerConfig{});
  int first_confirmed = -1;
  std::size_t duplicate_rounds = 0;
  for (int k = 0; k < kRounds; ++k) {
    const std::vector<Scan> scans = scans_at(k, net.stations, truths);
    ASSERT_EQ(scans[1].addresses, std::vector<Address>{kAircraft}) << "round " << k;
    ASSERT_TRUE(scans[0].addresses.empty()) << "a primary radar reports no address";
    net.round(k, scans);
    net.expect_agreement(k);
    if (confirmed(net.peers[0]) > 0 && first_confirmed < 0) first_confirmed = k;
    if (first_confirmed >= 0 && confirmed(net.peers[0]) != 1) ++duplicate_rounds;
  }
  EXPECT_GE(first_confirmed, 0);
  EXPECT_EQ(duplicate_rounds, 0U) << "rounds with other than one confirmed track";
  const auto& track =
      *std::find_if(net.peers[0].tracks().begin(), net.peers[0].tracks().end(),
                    [](const auto& t) { return t.status == TrackStatus::kConfirmed; });
  EXPECT_EQ(track.address, kAircraft);
  EXPECT_EQ(track.updated_by, (std::vector<int>{1, 2})) << "both stations update it";
}

TEST(Identity, OneBroadcastStartsATrackWithItsAddressAndVelocity) {
  const std::vector<TargetTruth> truths = {the_aircraft()};
  TrackerConfig config;
  config.initiation.min_stations = 2;  // an unaddressed detection alone starts nothing
  Network net({radar_and_receiver()[1]}, config);
  const std::vector<Scan> scans = scans_at(0, net.stations, truths);
  net.round(0, scans);
  net.expect_agreement(0);
  ASSERT_EQ(net.peers[0].tracks().size(), 1U);
  const auto& track = net.peers[0].tracks()[0];
  EXPECT_EQ(track.address, kAircraft);
  EXPECT_EQ(track.status, TrackStatus::kTentative);
  const Detection& z = scans[0].detections[0];
  EXPECT_EQ(track.filter.mean.segment<3>(3), z.segment<3>(3)) << "the reported velocity";
  EXPECT_EQ(Covariance<3>(track.filter.covariance.block<3, 3>(3, 3)),
            Covariance<3>(broadcast_noise().block<3, 3>(3, 3)));

  // Without its address the same report starts nothing.
  Network anonymous({radar_and_receiver()[1]}, config);
  std::vector<Scan> unaddressed = scans;
  unaddressed[0].addresses.clear();
  anonymous.round(0, unaddressed);
  EXPECT_TRUE(anonymous.peers[0].tracks().empty());
}

TEST(Identity, ASpoofedAddressIsRefusedCountedAndDoesNotPullTheTrack) {
  const std::vector<TargetTruth> truths = {the_aircraft()};
  Network net(radar_and_receiver(), TrackerConfig{});
  Network twin(radar_and_receiver(), TrackerConfig{});  // the same run, without the spoof
  constexpr int kSpoofed = 20;
  for (int k = 0; k <= kSpoofed; ++k) {
    std::vector<Scan> scans = scans_at(k, net.stations, truths);
    std::vector<Scan> honest = scans;
    if (k == kSpoofed) {
      // The broadcast claims the aircraft's address from 2 km away; the twin hears nothing.
      ASSERT_EQ(scans[1].detections.size(), 1U);
      scans[1].detections[0](0) += 2000.0;
      honest[1].detections.clear();
      honest[1].addresses.clear();
    }
    const std::vector<Peer::Report> reports = net.round(k, scans);
    twin.round(k, honest);
    net.expect_agreement(k);
    if (k < kSpoofed) continue;
    EXPECT_EQ(reports[1].refused_addresses, 1U);
    EXPECT_TRUE(reports[1].pairs.empty()) << "it updates no track";
    EXPECT_TRUE(reports[1].unassociated.empty()) << "and starts none";
    EXPECT_EQ(net.center.refused_addresses(), 1U);
  }
  ASSERT_EQ(net.peers[0].tracks().size(), twin.peers[0].tracks().size());
  for (std::size_t t = 0; t < twin.peers[0].tracks().size(); ++t) {
    const auto& mine = net.peers[0].tracks()[t];
    const auto& theirs = twin.peers[0].tracks()[t];
    EXPECT_EQ(mine.address, theirs.address);
    EXPECT_EQ(mine.filter.mean, theirs.filter.mean) << "the spoof did not pull the track";
  }
}

// Two tracks a few metres apart, each holding an address, and one without.
Peer three_tracks(const TrackerConfig& config) {
  Peer peer(PeerTracks(Network::motion(), Network::variance()), radar_and_receiver(), config);
  std::vector<Peer::TrackType> tracks;
  const auto add = [&](TrackId id, const Vector3& p, Address address) {
    GaussianState<N> x;
    x.mean = Vector<N>::Zero();
    x.mean.head<3>() = p;
    x.covariance = Covariance<N>::Identity() * 400.0;
    Peer::TrackType track{id, TrackStatus::kConfirmed, {}, x, {}};
    track.address = address;
    tracks.push_back(track);
  };
  add(1, Vector3(0.0, 0.0, 300.0), 0xA1);
  add(2, Vector3(30.0, 0.0, 300.0), 0xB2);
  add(3, Vector3(0.0, 500.0, 300.0), kNoAddress);
  peer.restore(std::move(tracks));
  return peer;
}

Detection broadcast_at(const Vector3& p) {
  Vector<6> z = Vector<6>::Zero();
  z.head<3>() = p;
  return Detection(z);
}

TEST(Identity, AnAddressedDetectionGoesToTheTrackOfItsAddressAndNeverToAnother) {
  const Peer peer = three_tracks(TrackerConfig{});
  const Station receiver = radar_and_receiver()[1];
  Scan scan{2, broadcast_noise(), {}, {}};
  // On track 1's position but claiming track 2's address (30 m away: within the sanity gate).
  scan.detections.push_back(broadcast_at(Vector3(0.0, 0.0, 300.0)));
  scan.addresses.push_back(0xB2);
  // On track 1's position with an address no track holds: not track 1's, which holds another.
  scan.detections.push_back(broadcast_at(Vector3(1.0, 0.0, 300.0)));
  scan.addresses.push_back(0xC3);
  // On the unaddressed track 3 with an address no track holds: gated as any detection.
  scan.detections.push_back(broadcast_at(Vector3(0.0, 501.0, 300.0)));
  scan.addresses.push_back(0xD4);
  AssociationWork work;
  const ScanAssociation decided = peer.associate(receiver, scan, work);
  ASSERT_EQ(decided.pairs.size(), 2U);
  EXPECT_EQ(decided.pairs[0].track, 1) << "track 2 (index 1) holds 0xB2";
  EXPECT_EQ(decided.pairs[0].detection, 0U);
  EXPECT_EQ(decided.pairs[1].track, 2) << "the unaddressed track";
  EXPECT_EQ(decided.pairs[1].detection, 2U);
  EXPECT_EQ(decided.unassociated, std::vector<std::uint32_t>{1}) << "left to start a track";
  EXPECT_EQ(decided.refused_addresses, 0U);
  for (const Hypothesis& h : work.hypotheses.pairs) {
    EXPECT_FALSE(h.track < 2 && h.detection == 1) << "a pair with a track of another address";
    EXPECT_NE(h.detection, 0) << "a routed detection is not searched";
  }
}

TEST(Identity, AnUnaddressedTrackTakesTheAddressOfItsDetectionAtEveryPeerAndTheCenter) {
  const TrackerConfig config;
  std::vector<Peer> peers = {three_tracks(config), three_tracks(config)};
  Center center(CenterStackedTracks<Model>(Network::motion(), Network::variance()),
                radar_and_receiver(), config);
  center.restore({peers[0].tracks().begin(), peers[0].tracks().end()});
  const std::vector<Station> stations = radar_and_receiver();
  Scan radar{1, radar_noise(), {}, {}};
  Scan receiver{2, broadcast_noise(), {}, {}};
  receiver.detections.push_back(broadcast_at(Vector3(0.0, 501.0, 300.0)));
  receiver.addresses.push_back(0xD4);
  const std::vector<Scan> scans = {radar, receiver};
  test::play_picture_round(5, peers, center, std::span<const Station>(stations),
                           std::span<const Scan>(scans));
  for (const auto* tracks : {&peers[0], &peers[1]}) {
    ASSERT_EQ(tracks->tracks().size(), 3U) << "no track started for the address";
    EXPECT_EQ(tracks->tracks()[2].address, 0xD4U);
  }
  EXPECT_EQ(center.tracks()[2].address, 0xD4U);
  EXPECT_EQ(peers[0].digest(), peers[1].digest());
}

// One aircraft held twice, by its addressed track (1) and by an unaddressed one a few metres off
// (2) that its broadcast did not gate with, beside an unaddressed track crossing it (3).
Peer held_twice(const TrackerConfig& config) {
  Peer peer(PeerTracks(Network::motion(), Network::variance()), radar_and_receiver(), config);
  std::vector<Peer::TrackType> tracks;
  const auto add = [&](TrackId id, const Vector3& p, const Vector3& v, Address address) {
    GaussianState<N> x;
    x.mean << p, v;
    x.covariance = Covariance<N>::Zero();
    x.covariance.diagonal() << 25.0, 25.0, 25.0, 1.0, 1.0, 1.0;
    Peer::TrackType track{id, TrackStatus::kConfirmed, {}, x, {}};
    track.address = address;
    tracks.push_back(track);
  };
  add(1, Vector3(0.0, 0.0, 300.0), Vector3(30.0, 0.0, 0.0), kAircraft);
  add(2, Vector3(5.0, -3.0, 304.0), Vector3(30.5, 0.0, 0.0), kNoAddress);
  add(3, Vector3(2.0, 4.0, 300.0), Vector3(0.0, 30.0, 0.0), kNoAddress);
  peer.restore(std::move(tracks));
  return peer;
}

TEST(Identity, AnUnaddressedTrackHoldingAnAddressedTracksAircraftIsDroppedAtEveryNode) {
  const std::vector<Station> stations = radar_and_receiver();
  const std::vector<Scan> nothing = {Scan{1, radar_noise(), {}, {}},
                                     Scan{2, broadcast_noise(), {}, {}}};
  for (const double merge : {0.99, 0.0}) {
    TrackerConfig config;
    config.identity.merge_probability = merge;
    std::vector<Peer> peers = {held_twice(config), held_twice(config)};
    Center center(CenterStackedTracks<Model>(Network::motion(), Network::variance()), stations,
                  config);
    center.restore({peers[0].tracks().begin(), peers[0].tracks().end()});
    for (Peer& peer : peers) peer.predict();
    center.predict();
    std::vector<Peer::Report> reports;
    AssociationWork work;
    for (std::size_t s = 0; s < stations.size(); ++s) {
      reports.push_back(peers[s].report(stations[s], nothing[s], work));
    }
    const std::size_t dropped = merge > 0.0 ? 1 : 0;
    for (Peer& peer : peers) EXPECT_EQ(peer.fuse(7, reports).merged, dropped) << merge;
    EXPECT_EQ(center.update(7, nothing).merged, dropped) << merge;

    const std::vector<TrackId> kept =
        merge > 0.0 ? std::vector<TrackId>{1, 3} : std::vector<TrackId>{1, 2, 3};
    const auto ids = [](const auto& node) {
      std::vector<TrackId> out;
      for (const auto& track : node.tracks()) out.push_back(track.id);
      return out;
    };
    EXPECT_EQ(ids(peers[0]), kept) << "merge probability " << merge;
    EXPECT_EQ(ids(center), kept) << "merge probability " << merge;
    EXPECT_EQ(peers[0].digest(), peers[1].digest());
    EXPECT_EQ(peers[0].tracks()[0].address, kAircraft) << "the aircraft keeps its addressed track";
  }
}

TEST(Identity, AnAddressChangesThePicturesDigestAndNoAddressLeavesItAsBefore) {
  const TrackerConfig config;
  Peer addressed = three_tracks(config);
  auto tracks = std::vector<Peer::TrackType>(addressed.tracks().begin(), addressed.tracks().end());
  for (auto& track : tracks) track.address = kNoAddress;
  Peer plain = three_tracks(config);
  plain.restore(tracks);
  EXPECT_NE(addressed.digest(), plain.digest());

  PictureDigest before(tracks.size());
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    before.add(tracks[i].id, tracks[i].status, plain.estimates()[i].mean,
               plain.estimates()[i].covariance);
  }
  EXPECT_EQ(plain.digest(), before.value());
}

TEST(Identity, ACooperativeSensorHearsOnlyAircraftWithAnAddressAndListsEach) {
  std::vector<TargetTruth> truths = {
      straight_aircraft(0x111111, Vector3(0.0, 0.0, 300.0), Vector3(30.0, 0.0, 0.0)),
      straight_aircraft(kNoAddress, Vector3(500.0, 0.0, 300.0), Vector3(0.0, 30.0, 0.0)),
      straight_aircraft(0x333333, Vector3(0.0, 900.0, 300.0), Vector3(-30.0, 0.0, 0.0))};
  const Station receiver = radar_and_receiver()[1];
  DetectionConfig d = receiver_detection();
  d.clutter_per_scan = 3.0;
  d.field_of_view.max_range_m = 5000.0;
  for (int k = 0; k < 5; ++k) {
    ScanOrigins origins;
    const Scan scan = simulate_scan(2, test::truth_sensor_of(receiver), Vector3::Zero(),
                                    receiver.noise, d, truths, k, kSeed, 0, &origins);
    ASSERT_EQ(scan.addresses.size(), scan.detections.size());
    std::size_t heard = 0;
    for (std::size_t j = 0; j < scan.detections.size(); ++j) {
      const int o = origins.target[j];
      if (o < 0) {
        EXPECT_EQ(scan.addresses[j], kNoAddress) << "a false alarm has none";
        continue;
      }
      ++heard;
      EXPECT_NE(o, 1) << "the aircraft without an address is not heard";
      EXPECT_EQ(scan.addresses[j], truths[static_cast<std::size_t>(o)].address);
    }
    EXPECT_EQ(heard, 2U);
  }
}

}  // namespace
}  // namespace skyfuse
