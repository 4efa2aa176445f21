// A station's round of the picture on the wire, there and back: through the generated type's
// own serializer the values arrive bit for bit with the associations and the unassociated
// detections as sent, and a sample that is wrong anywhere is refused whole, by the first
// problem found.
#include "skyfuse/transport/picture_wire.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <initializer_list>
#include <limits>
#include <set>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "skyfuse/fusion/information_increment.hpp"
#include "skyfuse/models/constant_velocity.hpp"
#include "skyfuse/models/position_velocity.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/picture/picture_sensor.hpp"
#include "skyfuse/picture/track_filters.hpp"
#include "skyfuse/picture/track_table.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/tracking/ekf_increment_rule.hpp"
#include "skyfuse/tracking/imm_modes.hpp"
#include "skyfuse/transport/picture_callsigns.hpp"
#include "skyfuse/transport/picture_numbers.hpp"
#include "skyfuse/wire/skyfuse_picturePubSubTypes.h"
#include "transport/picture_world.hpp"

namespace skyfuse::transport {
namespace {

using Sensor = RangeAzimuthElevation<6>;
using Report = StationReport<InformationIncrement<6>>;
constexpr std::size_t kBound = 64;

// The sending station's radar (its site does not go on the wire).
PictureSensor<6> radar() {
  return Sensor(Vector3(100.0, -200.0, 30.0));
}

// Four detections: tracks 5 and 9 took detections 2 and 0; 1 and 3 are unassociated.
struct Sent {
  Scan scan;
  Report report;
};

Sent a_round() {
  Sent sent;
  sent.scan.station_id = 4;
  for (const Vector3& z : {Vector3(1500.125, 0.25, 0.0625), Vector3(2000.0, -1.5, 0.125),
                           Vector3(1234.5678901234567, 3.0, -0.5), Vector3(99.0, 0.0, 1.5)}) {
    sent.scan.detections.emplace_back(z);
  }
  sent.report.station_id = 4;
  sent.report.updates.resize(2);
  sent.report.updates[0].track = 5;
  sent.report.updates[1].track = 9;
  sent.report.pairs = {{5, 2, 1.0}, {9, 0, 1.0}};
  sent.report.unassociated = {{1, sent.scan.detections[1]}, {3, sent.scan.detections[3]}};
  sent.report.dropped = 1;
  return sent;
}

// A sample through its generated type's serializer, as DDS would carry it.
template <typename PubSubType, typename Sample>
Sample through_serializer(Sample sample) {
  PubSubType type;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(type.getSerializedSizeProvider(&sample)());
  EXPECT_TRUE(type.serialize(&sample, &payload));
  Sample back;
  EXPECT_TRUE(type.deserialize(&payload, &back));
  return back;
}
wire::PictureState through_cdr(wire::PictureState sample) {
  return through_serializer<wire::PictureStatePubSubType>(std::move(sample));
}
wire::PictureScan through_cdr(wire::PictureScan sample) {
  return through_serializer<wire::PictureScanPubSubType>(std::move(sample));
}
wire::PictureRound through_cdr(wire::PictureRound sample) {
  return through_serializer<wire::PictureRoundPubSubType>(std::move(sample));
}

TEST(PictureWire, ARoundArrivesAsSentThroughTheSerializer) {
  const Sent sent = a_round();
  const wire::PictureScan sample =
      through_cdr(to_wire<6>(radar(), sent.scan, sent.report, 42, 17, 0xfeedfacecafef00dULL));
  EXPECT_EQ(std::string(sample.sensor().c_str()), Sensor::kKind);
  EXPECT_EQ(sample.measurement_dim(), 3U);
  const auto [received, why] = picture_scan_from_wire(sample, Sensor::kKind, kBound);
  ASSERT_EQ(why, std::nullopt);
  ASSERT_TRUE(received.has_value());
  EXPECT_EQ(sample.run_id(), 42U);
  EXPECT_EQ(received->station_id, 4);
  EXPECT_EQ(received->step, 17U);
  EXPECT_EQ(received->picture_digest, 0xfeedfacecafef00dULL);
  EXPECT_EQ(received->dropped, 1U);
  ASSERT_EQ(received->detections.size(), sent.scan.detections.size());
  for (std::size_t j = 0; j < sent.scan.detections.size(); ++j) {
    EXPECT_TRUE(same_detection(received->detections[j], sent.scan.detections[j]))
        << "detection " << j;
  }
  EXPECT_EQ(received->associations, (std::vector<ReportedPair>{{5, 2, 1.0}, {9, 0, 1.0}}));
  EXPECT_EQ(received->unassociated, (std::vector<std::uint32_t>{1, 3}));
  EXPECT_TRUE(received->addresses.empty()) << "a primary radar's scan has no addresses";
}

TEST(PictureWire, EachDetectionsAddressAndTheRefusedCountArriveAsSent) {
  Sent sent = a_round();
  sent.scan.addresses = {0xABCDEF, kNoAddress, 0x123456, 0xFFFFFFFF};
  sent.report.refused_addresses = 2;
  const wire::PictureScan sample =
      through_cdr(to_wire<6>(radar(), sent.scan, sent.report, 1, 3, 0));
  const auto [received, why] = picture_scan_from_wire(sample, Sensor::kKind, kBound);
  ASSERT_TRUE(received.has_value());
  EXPECT_EQ(received->addresses, sent.scan.addresses);
  EXPECT_EQ(received->refused_addresses, 2U);

  wire::PictureScan short_of_one = sample;
  short_of_one.addresses().pop_back();
  const auto [refused, refused_why] = picture_scan_from_wire(short_of_one, Sensor::kKind, kBound);
  EXPECT_FALSE(refused.has_value()) << "addresses neither none nor one per detection";
  EXPECT_EQ(refused_why, DropKind::kOutOfRange);
}

// Each detection's callsign arrives as sent beside its address; a list that is neither none
// nor one per detection, or an identification that is no callsign, refuses the sample.
TEST(PictureWire, EachDetectionsIdentificationArrivesAsSent) {
  Sent sent = a_round();
  sent.scan.addresses = {0xABCDEF, kNoAddress, 0x123456, 0xF00011};
  sent.scan.identifications = {*identification_of("KLM1023"), kNoIdentification, kNoIdentification,
                               *identification_of("SFF00011")};
  const wire::PictureScan sample =
      through_cdr(to_wire<6>(radar(), sent.scan, sent.report, 1, 3, 0));
  const auto [received, why] = picture_scan_from_wire(sample, Sensor::kKind, kBound);
  ASSERT_TRUE(received.has_value());
  EXPECT_EQ(received->identifications, sent.scan.identifications);

  const auto refused = [&](const std::function<void(wire::PictureScan&)>& forge) {
    wire::PictureScan wrong = sample;
    forge(wrong);
    const auto [scan, wrong_why] = picture_scan_from_wire(wrong, Sensor::kKind, kBound);
    return !scan.has_value() && wrong_why == DropKind::kOutOfRange;
  };
  EXPECT_TRUE(refused([](auto& w) { w.identifications().pop_back(); }));
  EXPECT_TRUE(refused([](auto& w) { w.identifications()[0] = 0x6B6C6D0000000000ULL; }))
      << "lower case";
  EXPECT_TRUE(refused([](auto& w) { w.identifications()[0] = 0x4100410000000000ULL; }))
      << "a character after the padding";
  EXPECT_TRUE(refused([](auto& w) { w.identifications()[0] = 0x4120000000000000ULL; }))
      << "ends in a space";
}

// A node's book of callsigns: the newest a round's scans give for an address replaces the one
// before; a detection without an address or a callsign teaches nothing; a round's tracks are
// named by their addresses; the book travels in the whole picture, and a wrong one is refused.
TEST(PictureWire, ANodesCallsignsNameItsTracksAndTravelWithTheWholePicture) {
  CallsignBook book;
  const std::vector<Address> addresses{0x3C6444, kNoAddress, 0x4B1801, 0xF00002};
  book.learn(addresses,
             std::vector<Identification>{*identification_of("DLH4AB"), *identification_of("NOADDR"),
                                         kNoIdentification, *identification_of("SFF00002")});
  book.learn(addresses, {});  // none has a callsign
  book.learn(std::vector<Address>{0x3C6444},
             std::vector<Identification>{*identification_of("DLH5")});
  EXPECT_EQ(callsign_of(book.of(0x3C6444)), "DLH5");
  EXPECT_EQ(book.of(0x4B1801), kNoIdentification);
  EXPECT_EQ(book.of(kNoAddress), kNoIdentification);
  EXPECT_EQ(book.entries().size(), 2U);

  wire::PictureRound round;
  round.tracks().resize(3);
  round.tracks()[0].address(0xF00002);
  round.tracks()[1].address(0x4B1801);
  identify_round(book, round);
  EXPECT_EQ(callsign_of(round.tracks()[0].identification()), "SFF00002");
  EXPECT_EQ(round.tracks()[1].identification(), kNoIdentification);
  EXPECT_EQ(round.tracks()[2].identification(), kNoIdentification);
  EXPECT_EQ(through_cdr(round).tracks()[0].identification(), round.tracks()[0].identification());

  wire::PictureState state;
  callsigns_to_wire(book, state);
  const wire::PictureState back = through_cdr(state);
  const auto entries = callsigns_from_wire(back);
  ASSERT_TRUE(entries.has_value());
  EXPECT_EQ(*entries, book.entries());
  const auto refused = [&](const std::function<void(wire::PictureState&)>& forge) {
    wire::PictureState wrong = back;
    forge(wrong);
    return !callsigns_from_wire(wrong).has_value();
  };
  EXPECT_TRUE(refused([](auto& w) { std::swap(w.callsigns()[0], w.callsigns()[1]); }));
  EXPECT_TRUE(refused([](auto& w) { w.callsigns()[0].address(0); }));
  EXPECT_TRUE(refused([](auto& w) { w.callsigns()[0].identification(0); }));
  EXPECT_TRUE(refused([](auto& w) { w.callsigns()[0].identification(0x6100000000000000ULL); }));
}

TEST(PictureWire, AnEmptyScanArrivesEmpty) {
  const wire::PictureScan sample = through_cdr(to_wire<6>(radar(), Scan{}, Report{}, 1, 0, 0));
  const auto [received, why] = picture_scan_from_wire(sample, Sensor::kKind, kBound);
  ASSERT_TRUE(received.has_value());
  EXPECT_TRUE(received->detections.empty());
  EXPECT_TRUE(received->associations.empty());
  EXPECT_TRUE(received->unassociated.empty());
}

// The refusals, each on an otherwise good sample.
struct Forgery {
  const char* what;
  std::function<void(wire::PictureScan&)> forge;
  DropKind why;
};

TEST(PictureWire, ASampleWrongAnywhereIsRefusedWhole) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Forgery> forgeries = {
      {"another sensor kind", [](auto& s) { s.sensor("position_velocity"); },
       DropKind::kOutOfRange},
      {"another dimension", [](auto& s) { s.measurement_dim(6); }, DropKind::kOutOfRange},
      {"a detection cut short", [](auto& s) { s.values().pop_back(); }, DropKind::kOutOfRange},
      {"a value not finite", [&](auto& s) { s.values()[4] = nan; }, DropKind::kNonFinite},
      {"a range the sensor cannot report", [](auto& s) { s.values()[3] = -5.0; },
       DropKind::kOutOfRange},
      {"more detections than the bound",
       [](auto& s) { s.values().resize((kBound + 1) * 3, 100.0); }, DropKind::kOutOfRange},
      {"an association beyond the scan", [](auto& s) { s.associations()[1].detection(4); },
       DropKind::kOutOfRange},
      {"a track twice", [](auto& s) { s.associations()[1].track_id(5); }, DropKind::kOutOfRange},
      {"tracks out of order", [](auto& s) { s.associations()[1].track_id(3); },
       DropKind::kOutOfRange},
      {"a detection associated twice", [](auto& s) { s.associations()[1].detection(2); },
       DropKind::kOutOfRange},
      {"a weight of 0", [](auto& s) { s.associations()[0].weight(0.0); }, DropKind::kOutOfRange},
      {"a weight above 1", [](auto& s) { s.associations()[0].weight(1.5); }, DropKind::kOutOfRange},
      {"a weight not finite", [&](auto& s) { s.associations()[0].weight(nan); },
       DropKind::kNonFinite},
      {"a detection's weights summing past 1",
       [](auto& s) {
         s.associations()[0].weight(0.6);
         s.associations()[1].weight(0.6);
         s.associations()[1].detection(2);
       },
       DropKind::kOutOfRange},
      {"a detection associated and unassociated", [](auto& s) { s.unassociated()[0] = 2; },
       DropKind::kOutOfRange},
      {"unassociated out of order",
       [](auto& s) {
         s.unassociated() = {3, 1};
       },
       DropKind::kOutOfRange},
      {"an unassociated index beyond the scan", [](auto& s) { s.unassociated()[1] = 7; },
       DropKind::kOutOfRange},
  };
  const Sent sent = a_round();
  const wire::PictureScan good = to_wire<6>(radar(), sent.scan, sent.report, 42, 17, 0);
  ASSERT_TRUE(picture_scan_from_wire(good, Sensor::kKind, kBound).first.has_value());
  for (const Forgery& forgery : forgeries) {
    wire::PictureScan forged = good;
    forgery.forge(forged);
    const auto [received, why] = picture_scan_from_wire(forged, Sensor::kKind, kBound);
    EXPECT_FALSE(received.has_value()) << forgery.what;
    EXPECT_EQ(why, forgery.why) << forgery.what;
  }
}

// In a picture of stations of different sensors, a sample is read as its station's sensor's: a
// position-velocity station's six values a detection arrive bit for bit, and the same sample
// claiming to be from the radar station, or relabelled as the radar's kind, is refused.
TEST(PictureWire, EachStationsSampleIsCheckedAgainstItsOwnSensor) {
  using Pv = PositionVelocity<6>;
  const std::vector<KnownStation<6>> stations = {{4, radar(), Covariance<3>::Identity(), 1.0, {}},
                                                 {5, Pv(), Covariance<6>::Identity(), 1.0, {}}};
  const StationSensorKinds kinds{std::span<const KnownStation<6>>(stations)};
  Scan scan;
  scan.station_id = 5;
  Vector<6> z;
  z << 1500.125, -20.5, 300.0625, 12.0, -3.5, 0.25;
  scan.detections.emplace_back(z);
  scan.detections.emplace_back(Vector<6>(z.reverse()));
  Report report;
  report.station_id = 5;
  report.unassociated = {{0, scan.detections[0]}, {1, scan.detections[1]}};
  const wire::PictureScan sample =
      through_cdr(to_wire<6>(stations[1].sensor, scan, report, 1, 3, 0));
  EXPECT_EQ(std::string(sample.sensor().c_str()), Pv::kKind);
  EXPECT_EQ(sample.measurement_dim(), 6U);
  const auto [received, why] = picture_scan_from_wire(sample, kinds, kBound);
  ASSERT_TRUE(received.has_value());
  ASSERT_EQ(received->detections.size(), 2U);
  for (std::size_t j = 0; j < 2; ++j) {
    EXPECT_EQ(received->detections[j].size(), 6);
    EXPECT_TRUE(same_detection(received->detections[j], scan.detections[j])) << "detection " << j;
  }

  wire::PictureScan as_the_radar = sample;
  as_the_radar.station_id(4);
  EXPECT_EQ(picture_scan_from_wire(as_the_radar, kinds, kBound).second, DropKind::kOutOfRange);
  wire::PictureScan relabelled = sample;
  relabelled.sensor(std::string(Sensor::kKind));
  EXPECT_EQ(picture_scan_from_wire(relabelled, kinds, kBound).second, DropKind::kOutOfRange);
}

// A peer that rebuilds every station's report from the station's sample (`scan_of` station
// index s's scan of round k), beside a peer that fuses the stations' own reports, round after
// round: each round both hold the same picture, bit for bit. Returns the last round's digest.
std::uint64_t expect_rebuilt_reports_hold_the_stations_picture(
    const test::PictureWorld& world, int rounds,
    const std::function<Scan(std::size_t, int)>& scan_of) {
  using Peer = test::PictureWorld::Peer;
  const auto& stations = world.stations;
  const StationSensorKinds kinds{std::span<const test::PictureWorld::Station>(stations)};
  Peer own = world.empty_picture();      // fuses the stations' own reports
  Peer rebuilt = world.empty_picture();  // fuses the reports rebuilt from the wire
  AssociationWork work;
  std::size_t updates = 0;
  for (int k = 0; k < rounds; ++k) {
    own.predict();
    rebuilt.predict();
    std::vector<Peer::Report> sent;
    std::vector<Peer::Report> received;
    for (std::size_t s = 0; s < stations.size(); ++s) {
      const auto& station = stations[s];
      const Scan scan = scan_of(s, k);
      sent.push_back(own.report(station, scan, work));
      updates += sent.back().updates.size();
      const auto [scan_back, why] = picture_scan_from_wire(
          through_cdr(to_wire<6>(station.sensor, scan, sent.back(), 1,
                                 static_cast<std::uint32_t>(k), own.digest())),
          kinds, kBound);
      EXPECT_TRUE(scan_back.has_value()) << "round " << k;
      if (!scan_back) return 0;
      EXPECT_EQ(scan_back->picture_digest, rebuilt.digest()) << "the same predicted picture";
      auto report = rebuilt.report_of(station, published(*scan_back), scan_back->associations,
                                      scan_back->unassociated, scan_back->dropped);
      EXPECT_TRUE(report.has_value()) << "round " << k;
      if (!report) return 0;
      received.push_back(std::move(*report));
    }
    own.fuse(static_cast<std::uint64_t>(k), sent);
    rebuilt.fuse(static_cast<std::uint64_t>(k), received);
    EXPECT_EQ(own.tracks().size(), rebuilt.tracks().size()) << "round " << k;
    if (own.tracks().size() != rebuilt.tracks().size()) return 0;
    EXPECT_EQ(own.digest(), rebuilt.digest()) << "round " << k;
    for (std::size_t t = 0; t < own.tracks().size(); ++t) {
      EXPECT_EQ(own.tracks()[t].id, rebuilt.tracks()[t].id);
      EXPECT_EQ(own.tracks()[t].status, rebuilt.tracks()[t].status);
      EXPECT_EQ(own.tracks()[t].updated_by, rebuilt.tracks()[t].updated_by);
      EXPECT_EQ(own.estimates()[t].mean, rebuilt.estimates()[t].mean) << "round " << k;
      EXPECT_EQ(own.estimates()[t].covariance, rebuilt.estimates()[t].covariance);
    }
  }
  EXPECT_GE(own.tracks().size(), 5U) << "every aircraft tracked";
  EXPECT_GT(updates, 100U) << "the rounds associated detections to tracks";
  return own.digest();
}

// Five aircraft crossing in front of three radars, P_D 0.9 and two false alarms a scan: every
// peer that rebuilds every station's report from the station's sample holds, round after round,
// the picture of a peer that fused the stations' own reports, bit for bit.
TEST(PictureWire, PeersRebuildingEveryReportFromTheWireHoldTheStationsPictureBitForBit) {
  constexpr int kRounds = 20;
  const test::PictureWorld world(kRounds);
  expect_rebuilt_reports_hold_the_stations_picture(
      world, kRounds, [&](std::size_t s, int k) { return world.scan(s, k); });
}

// The same, each detection's report stating its own σ of some values (Scan::reported_std, as an
// ADS-B report's NACp does): the stated σ travel with the sample, every peer rebuilds each
// report with them and holds the stations' picture bit for bit — and that picture is not the
// one of the station's own noise, so the stated σ were used.
TEST(PictureWire, StatedSigmasTravelWithTheScanAndEveryPeerUsesThem) {
  constexpr int kRounds = 20;
  const test::PictureWorld world(kRounds);
  const auto stated = [&](std::size_t s, int k) {
    Scan scan = world.scan(s, k);
    for (std::size_t j = 0; j < scan.detections.size(); ++j) {
      Detection std_of = Detection::Zero(scan.detections[j].size());
      // Range stated 1.5 to 3 times the station's σ; the angles left to the station's noise.
      std_of(0) = (1.5 + 0.5 * static_cast<double>(j % 4)) * std::sqrt(scan.noise(0, 0));
      scan.reported_std.push_back(std_of);
    }
    const wire::PictureScan sample = to_wire<6>(world.stations[s].sensor, scan, Report{}, 1, 0, 0);
    EXPECT_EQ(sample.reported_std().size(), scan.detections.size() * 3U);
    return scan;
  };
  const std::uint64_t plain = expect_rebuilt_reports_hold_the_stations_picture(
      world, kRounds, [&](std::size_t s, int k) { return world.scan(s, k); });
  const std::uint64_t with_stated =
      expect_rebuilt_reports_hold_the_stations_picture(world, kRounds, stated);
  EXPECT_NE(plain, with_stated) << "the stated σ changed the updates";
}

// Stated σ neither none nor one set per detection, negative or not finite: the sample is refused.
TEST(PictureWire, WrongStatedSigmasAreRefused) {
  const test::PictureWorld world(2);
  const StationSensorKinds kinds{std::span<const test::PictureWorld::Station>(world.stations)};
  Scan scan = world.scan(0, 0);
  ASSERT_GE(scan.detections.size(), 2U);
  for (const Detection& z : scan.detections)
    scan.reported_std.push_back(Detection::Constant(z.size(), 2.0));
  const wire::PictureScan good =
      through_cdr(to_wire<6>(world.stations[0].sensor, scan, Report{}, 1, 0, 0));
  const auto [received, why] = picture_scan_from_wire(good, kinds, kBound);
  ASSERT_TRUE(received.has_value());
  ASSERT_EQ(received->reported_std.size(), scan.detections.size());
  EXPECT_TRUE(same_detection(received->reported_std[1], scan.reported_std[1]));

  wire::PictureScan short_by_one = good;
  short_by_one.reported_std().pop_back();
  EXPECT_EQ(picture_scan_from_wire(short_by_one, kinds, kBound).second, DropKind::kOutOfRange);
  wire::PictureScan negative = good;
  negative.reported_std()[4] = -1.0;
  EXPECT_EQ(picture_scan_from_wire(negative, kinds, kBound).second, DropKind::kOutOfRange);
  wire::PictureScan not_finite = good;
  not_finite.reported_std()[2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(picture_scan_from_wire(not_finite, kinds, kBound).second, DropKind::kNonFinite);
}

// A station's whole picture, sent to a peer that has parted from it: taken back through the
// serializer, it is the same picture bit for bit (ids, statuses, histories, states, updaters),
// and a sample wrong anywhere is refused whole.
TEST(PictureWire, AWholePictureArrivesBitForBitAndAWrongOneIsRefused) {
  using Peer = test::PictureWorld::Peer;
  const test::PictureWorld world(12);
  Peer sender = world.empty_picture();
  AssociationWork work;
  for (int k = 0; k < 12; ++k) world.play_round(sender, k, work);
  ASSERT_GE(sender.tracks().size(), 5U);
  const wire::PictureState sent = picture_state_to_wire(sender, 1, 11, 2);
  const wire::PictureState back = through_cdr(sent);
  auto tracks = picture_state_from_wire(back, test::PictureWorld::track_filters());
  ASSERT_TRUE(tracks.has_value());

  Peer taker = world.empty_picture();
  taker.restore(std::move(*tracks));
  EXPECT_EQ(taker.digest(), sender.digest());
  EXPECT_EQ(back.picture_digest(), sender.digest());
  for (std::size_t t = 0; t < sender.tracks().size(); ++t) {
    EXPECT_EQ(taker.tracks()[t].history, sender.tracks()[t].history);
    EXPECT_EQ(taker.tracks()[t].updated_by, sender.tracks()[t].updated_by);
  }
  taker.predict();
  sender.predict();
  EXPECT_EQ(taker.digest(), sender.digest()) << "and predicts to the same picture";

  const auto refused = [&](const std::function<void(wire::PictureState&)>& forge) {
    wire::PictureState wrong = back;
    forge(wrong);
    return !picture_state_from_wire(wrong, test::PictureWorld::track_filters()).has_value();
  };
  EXPECT_TRUE(refused([](auto& w) { w.tracks()[1].track_id(w.tracks()[0].track_id()); }));
  EXPECT_TRUE(refused([](auto& w) { w.tracks()[0].x().pop_back(); }));
  EXPECT_TRUE(refused([](auto& w) { w.tracks()[0].covariance().pop_back(); }));
  EXPECT_TRUE(
      refused([](auto& w) { w.tracks()[0].x()[0] = std::numeric_limits<double>::quiet_NaN(); }));
  EXPECT_TRUE(refused([](auto& w) { w.tracks()[0].history_rounds(33); }));
  // One address held by two tracks.
  EXPECT_TRUE(refused([](auto& w) {
    w.tracks()[0].address(0xABC);
    w.tracks()[1].address(0xABC);
  }));
  wire::PictureState addressed = back;
  addressed.tracks()[0].address(0xABC);
  const auto with_address = picture_state_from_wire(addressed, test::PictureWorld::track_filters());
  ASSERT_TRUE(with_address.has_value());
  EXPECT_EQ((*with_address)[0].address, 0xABCU) << "a track's address travels with it";
  // An IMM's modes on a single-model track.
  EXPECT_TRUE(refused([](auto& w) { w.tracks()[0].mode_probabilities({1.0}); }));
  EXPECT_TRUE(refused([](auto& w) { w.tracks()[0].modes().resize(1); }));
}

// Twelve rounds of `world`'s picture, numbered round by round by each of `numberings`.
test::PictureWorld::Peer numbered_rounds(const test::PictureWorld& world,
                                         std::initializer_list<asterix::TrackNumbers*> numberings) {
  test::PictureWorld::Peer picture = world.empty_picture();
  AssociationWork work;
  std::vector<std::uint64_t> ids;
  for (int k = 0; k < 12; ++k) {
    world.play_round(picture, k, work);
    for (asterix::TrackNumbers* numbers : numberings) {
      number_picture(*numbers, picture, static_cast<std::uint64_t>(k), ids);
    }
  }
  return picture;
}

// A node's picture to the harness carries each track's short number as the node gave it (what
// its CAT062, the harness's record and labels show); a track the numbers ran out for carries 0.
TEST(PictureWire, ARoundCarriesEachTracksNumberAsItsNodeGaveIt) {
  const test::PictureWorld world(12);
  asterix::TrackNumbers numbers(1, 65535, 3);
  asterix::TrackNumbers three(1, 3, 3);  // fewer numbers than tracks
  const test::PictureWorld::Peer picture = numbered_rounds(world, {&numbers, &three});
  ASSERT_GE(picture.tracks().size(), 5U);
  wire::PictureRound round = picture_round_to_wire(picture, 1, 11, 2, 12);
  number_round(numbers, round);
  const wire::PictureRound back = through_cdr(round);
  ASSERT_EQ(back.tracks().size(), picture.tracks().size());
  std::set<std::uint16_t> given;
  for (const wire::PictureTrack& track : back.tracks()) {
    EXPECT_EQ(track.number(), numbers.number_of(track.track_id()).value());
    EXPECT_TRUE(given.insert(track.number()).second) << "a number per track";
  }
  number_round(three, round);
  int without = 0;
  for (const wire::PictureTrack& track : round.tracks()) {
    EXPECT_EQ(track.number(), three.number_of(track.track_id()).value_or(0));
    if (track.number() == 0) ++without;
  }
  EXPECT_EQ(without, static_cast<int>(picture.tracks().size()) - 3);
}

// A whole picture carries its sender's short track numbers: a taker that restores them numbers
// the next rounds as the sender does (TrackNumbers.ANodeThatTakesAPeersStateNumbers...); a
// numbering that is wrong is refused.
TEST(PictureWire, AWholePictureCarriesItsTrackNumbers) {
  const test::PictureWorld world(12);
  asterix::TrackNumbers numbers(1, 65535, 3);
  const test::PictureWorld::Peer sender = numbered_rounds(world, {&numbers});
  ASSERT_GE(sender.tracks().size(), 5U);
  wire::PictureState sent = picture_state_to_wire(sender, 1, 11, 2);
  track_numbers_to_wire(numbers, sent);
  const wire::PictureState back = through_cdr(sent);
  const auto state = track_numbers_from_wire(back);
  ASSERT_TRUE(state.has_value());
  EXPECT_EQ(*state, numbers.state());
  EXPECT_EQ(state->numbers.size(), sender.tracks().size());
  asterix::TrackNumbers taker(1, 65535, 3);
  taker.restore(*state);
  for (const auto& track : sender.tracks()) {
    EXPECT_EQ(taker.number_of(track.id), numbers.number_of(track.id));
    EXPECT_NE(taker.number_of(track.id), std::nullopt);
  }

  const auto refused = [&](const std::function<void(wire::PictureState&)>& forge) {
    wire::PictureState wrong = back;
    forge(wrong);
    return !track_numbers_from_wire(wrong).has_value();
  };
  EXPECT_TRUE(refused([](auto& w) { w.track_numbers()[0].number(0); }));
  EXPECT_TRUE(refused([](auto& w) { w.track_numbers()[1].number(w.track_numbers()[0].number()); }));
  EXPECT_TRUE(refused([](auto& w) { w.track_numbers()[1].key(w.track_numbers()[0].key()); }));
  EXPECT_TRUE(refused([](auto& w) { w.numbers_next(0); }));
  EXPECT_TRUE(refused([](auto& w) { w.numbers_free({5, 5}); }));
  EXPECT_TRUE(refused([](auto& w) {
    w.numbers_held().resize(2);
    w.numbers_held()[0].key(9);
    w.numbers_held()[0].number(7);
    w.numbers_held()[1].key(8);
    w.numbers_held()[1].number(8);
  }));
}

// A registering picture's state carries every station's registration sums: the taker holds
// the same estimates bit for bit, so it corrects the next scans as the sender does; sums of
// another size, not finite or out of order are refused, and a taker whose stations they are
// not refuses them.
TEST(PictureWire, ARegisteringPictureArrivesWithEveryStationsRegistration) {
  using Peer = test::PictureWorld::Peer;
  const test::PictureWorld world(12);
  TrackerConfig config;
  config.registration.kind = "least_squares";
  Peer sender = world.empty_picture(config);
  AssociationWork work;
  for (int k = 0; k < 11; ++k) world.play_round(sender, k, work);
  const wire::PictureState sent = picture_state_to_wire(sender, 1, 10, 2);
  ASSERT_EQ(sent.biases().size(), world.stations.size());
  EXPECT_GT(sent.biases()[0].detections(), 0U) << "the registration learnt something to send";
  const wire::PictureState back = through_cdr(sent);
  auto tracks = picture_state_from_wire(back, test::PictureWorld::track_filters());
  const auto biases = picture_biases_from_wire(back);
  ASSERT_TRUE(tracks.has_value());
  ASSERT_TRUE(biases.has_value());

  // Each EKF track's cross-covariances with the bias errors (registration/
  // considered_biases.hpp) travel with it, bit for bit.
  std::size_t considering = 0;
  for (std::size_t t = 0; t < sender.tracks().size(); ++t) {
    EXPECT_EQ((*tracks)[t].considered, sender.tracks()[t].considered) << "track " << t;
    if (!sender.tracks()[t].considered.empty()) ++considering;
  }
  EXPECT_GT(considering, 0U) << "registered stations' detections made the tracks keep some";

  Peer taker = world.empty_picture(config);
  taker.restore(std::move(*tracks));
  ASSERT_TRUE(taker.restore_biases(*biases));
  for (const auto& station : world.stations) {
    const SensorBias& mine = taker.bias_of(station.id).bias();
    const SensorBias& theirs = sender.bias_of(station.id).bias();
    EXPECT_TRUE(mine.range_m == theirs.range_m && mine.azimuth_rad == theirs.azimuth_rad &&
                mine.elevation_rad == theirs.elevation_rad && mine.time_s == theirs.time_s)
        << "station " << station.id;
  }
  // The next round, from the same scans: the same picture.
  world.play_round(taker, 11, work);
  world.play_round(sender, 11, work);
  EXPECT_EQ(taker.digest(), sender.digest());

  const auto refused = [&](const std::function<void(wire::PictureState&)>& forge) {
    wire::PictureState wrong = back;
    forge(wrong);
    return !picture_biases_from_wire(wrong).has_value();
  };
  EXPECT_TRUE(refused([](auto& w) { w.biases()[0].information().pop_back(); }));
  EXPECT_TRUE(refused([](auto& w) { w.biases()[0].information_vector().push_back(0.0); }));
  EXPECT_TRUE(refused([](auto& w) {
    w.biases()[0].information_vector()[0] = std::numeric_limits<double>::infinity();
  }));
  EXPECT_TRUE(refused([](auto& w) { w.biases()[1].station_id(w.biases()[0].station_id()); }));
  // A track's cross-covariances of a size no state and biases have, not finite, out of order.
  std::size_t t = 0;
  while (t < back.tracks().size() && back.tracks()[t].considered().size() < 2) ++t;
  ASSERT_LT(t, back.tracks().size()) << "a track kept two stations'";
  const auto track_refused = [&](const std::function<void(wire::PictureStateTrack&)>& forge) {
    wire::PictureState wrong = back;
    forge(wrong.tracks()[t]);
    return !picture_state_from_wire(wrong, test::PictureWorld::track_filters()).has_value();
  };
  EXPECT_TRUE(track_refused([](auto& w) { w.considered()[0].cross().pop_back(); }));
  EXPECT_TRUE(track_refused([](auto& w) { w.considered()[0].cross().clear(); }));
  EXPECT_TRUE(track_refused(
      [](auto& w) { w.considered()[0].cross()[0] = std::numeric_limits<double>::quiet_NaN(); }));
  EXPECT_TRUE(
      track_refused([](auto& w) { w.considered()[1].station_id(w.considered()[0].station_id()); }));
  // Sums the wire takes but the taker's stations are not: one missing, or of another station.
  Peer other = world.empty_picture(config);
  std::vector<BiasSums> missing = *biases;
  missing.pop_back();
  EXPECT_FALSE(other.restore_biases(missing));
  std::vector<BiasSums> renamed = *biases;
  renamed.back().station_id += 100;
  EXPECT_FALSE(other.restore_biases(renamed));
  // A picture that registers nothing sends none.
  EXPECT_TRUE(picture_state_to_wire(world.empty_picture(), 1, 0, 2).biases().empty());
}

// The same for an IMM's picture: each track's mode probabilities and every mode's state come
// back bit for bit, so the taker predicts to the sender's picture; a mode missing, a mode
// wrong, probabilities that are not, or a single model's state on an IMM track are refused.
TEST(PictureWire, AnImmPictureArrivesWithEveryModeBitForBit) {
  using Tracks = PeerImmTracks<DefaultImmModes>;
  using Table = TrackTable<Tracks>;
  constexpr int N = KinematicState::kDim;
  const Scenario scenario =
      load_scenario_file(std::string(SKYFUSE_BIN_DIR) + "/scenarios/paper000-imm.yaml");
  Table sender(Tracks(scenario), {}, TrackerConfig{});
  for (const TrackId id : {TrackId{3}, TrackId{7}, TrackId{12}}) {
    GaussianState<N> start;
    start.mean = Vector<N>::LinSpaced(-1.0, static_cast<double>(id));
    start.mean(KinematicState::kTurnRate) = 0.01 * static_cast<double>(id);
    start.covariance = Covariance<N>::Identity() * (1.0 + static_cast<double>(id));
    sender.add_known_track(id, start);
  }
  for (int k = 0; k < 5; ++k) sender.predict();

  wire::PictureStatePubSubType type;
  const wire::PictureState sent = picture_state_to_wire(sender, 1, 4, 2);
  ASSERT_EQ(sent.tracks().front().modes().size(), 3U);
  EXPECT_TRUE(sent.tracks().front().x().empty());
  eprosima::fastrtps::rtps::SerializedPayload_t payload(
      type.getSerializedSizeProvider(const_cast<wire::PictureState*>(&sent))());
  ASSERT_TRUE(type.serialize(const_cast<wire::PictureState*>(&sent), &payload));
  wire::PictureState back;
  ASSERT_TRUE(type.deserialize(&payload, &back));
  auto tracks = picture_state_from_wire(back, sender.filters());
  ASSERT_TRUE(tracks.has_value());

  Table taker(Tracks(scenario), {}, TrackerConfig{});
  taker.restore(std::move(*tracks));
  ASSERT_EQ(taker.tracks().size(), sender.tracks().size());
  for (std::size_t t = 0; t < sender.tracks().size(); ++t) {
    const auto& mine = taker.tracks()[t].filter.filter();
    const auto& theirs = sender.tracks()[t].filter.filter();
    EXPECT_EQ(mine.mode_probabilities(), theirs.mode_probabilities());
    Tracks::State::for_each_mode([&]<int I>(std::integral_constant<int, I>) {
      EXPECT_EQ(mine.template mode_state<I>().mean, theirs.template mode_state<I>().mean);
      EXPECT_EQ(mine.template mode_state<I>().covariance,
                theirs.template mode_state<I>().covariance);
    });
  }
  EXPECT_EQ(taker.digest(), sender.digest());
  taker.predict();
  sender.predict();
  EXPECT_EQ(taker.digest(), sender.digest()) << "and predicts to the same picture";

  const auto refused = [&](const std::function<void(wire::PictureState&)>& forge) {
    wire::PictureState wrong = back;
    forge(wrong);
    return !picture_state_from_wire(wrong, sender.filters()).has_value();
  };
  EXPECT_FALSE(refused([](auto&) {})) << "the sample itself is taken";
  EXPECT_TRUE(refused([](auto& w) { w.tracks()[0].modes().pop_back(); }));
  EXPECT_TRUE(refused([](auto& w) { w.tracks()[0].mode_probabilities().pop_back(); }));
  EXPECT_TRUE(refused([](auto& w) { w.tracks()[0].mode_probabilities()[0] += 0.1; }));
  EXPECT_TRUE(refused([](auto& w) { w.tracks()[0].modes()[1].x().pop_back(); }));
  EXPECT_TRUE(refused([](auto& w) { w.tracks()[0].modes()[2].covariance().pop_back(); }));
  EXPECT_TRUE(refused(
      [](auto& w) { w.tracks()[1].modes()[0].x()[0] = std::numeric_limits<double>::quiet_NaN(); }));
  EXPECT_TRUE(refused([](auto& w) { w.tracks()[0].x().push_back(1.0); }));
}

TEST(PictureWire, AReportNamingATrackThePictureLacksIsNotRebuilt) {
  using Model = ConstantVelocity3D;
  using TrackSensor = RangeAzimuthElevation<Model::kDim>;
  using Peer = PeerPicture<PeerModelTracks<Model, EkfIncrementRule>>;
  const KnownStation<Model::kDim> station{
      1, TrackSensor(Vector3(0.0, 0.0, 0.0)), Covariance<3>::Identity(), 1.0, {}};
  Peer picture(PeerModelTracks<Model, EkfIncrementRule>(Model(1.0, {0.5, 1.0}),
                                                        Vector<Model::kDim>::Constant(100.0)),
               {station}, TrackerConfig{});
  GaussianState<Model::kDim> known;
  known.mean << 1000.0, 0.0, 100.0, 0.0, 0.0, 0.0;
  known.covariance = Covariance<Model::kDim>::Identity();
  picture.add_known_track(7, known);
  const std::vector<Detection> detections = {Detection(Vector3(1005.0, 0.0, 0.1))};
  const std::vector<ReportedPair> known_track = {{7, 0, 1.0}};
  const std::vector<ReportedPair> unknown_track = {{8, 0, 1.0}};
  EXPECT_TRUE(picture.report_of(station, {detections}, known_track, {}, 0).has_value());
  EXPECT_FALSE(picture.report_of(station, {detections}, unknown_track, {}, 0).has_value());
}

}  // namespace
}  // namespace skyfuse::transport
