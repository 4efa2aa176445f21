// A station's scan as ASTERIX carries it and back (transport/scan_asterix.hpp), on uam-mixed's
// own scans: every detection of a Mode S radar and a Remote ID receiver survives the round trip
// within its items' resolutions, and a scan so quantised is quantised again to the same bits —
// what a station fed a recorded feed would hold.
#include "skyfuse/transport/scan_asterix.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "skyfuse/asterix/data_block.hpp"
#include "skyfuse/asterix/datagram.hpp"
#include "skyfuse/asterix/pcap.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/traffic/traffic_truth.hpp"
#include "skyfuse/transport/asterix_replay.hpp"

namespace skyfuse::transport {
namespace {

constexpr double kFootM = 0.3048;
constexpr double kNauticalMileM = 1852.0;

Scenario uam_mixed() {
  return load_scenario_file(std::string(SKYFUSE_BIN_DIR) + "/scenarios/uam-mixed.yaml");
}

TEST(ScanAsterix, EveryDetectionSurvivesWithinItsItemsResolutionAndQuantisesToTheSameBits) {
  const Scenario scenario = uam_mixed();
  const auto truth = build_traffic_truth(scenario).targets;
  constexpr int kStations = 10;
  std::size_t plots = 0;
  std::size_t reports = 0;
  std::size_t identified = 0;
  for (int k = 20; k < 24; ++k) {
    const auto scans = simulated_scans_at(scenario, truth, kStations, 0, k);
    for (std::size_t s = 0; s < scans.size(); ++s) {
      const SimulatedScan& scan = scans[s];
      const StationConfig& station = scenario.stations[s];
      const std::optional<Scan> once = quantised_as_asterix(scan, station, scenario);
      ASSERT_EQ(once.has_value(), carried_by_asterix(scan.sensor_kind)) << scan.sensor_kind;
      if (!once) continue;
      const auto& z = scan.scan.detections;
      const auto& q = once->detections;
      ASSERT_EQ(q.size(), z.size());
      EXPECT_EQ(once->addresses, scan.scan.addresses);
      // A report carries its callsign (I021/170), a Mode S plot its (I048/240).
      EXPECT_EQ(once->identifications, scan.scan.identifications);
      for (const Identification id : once->identifications) {
        identified += id != kNoIdentification ? 1U : 0U;
      }
      EXPECT_EQ(once->station_id, station.id);
      for (std::size_t j = 0; j < z.size(); ++j) {
        ASSERT_EQ(q[j].size(), z[j].size());
        if (scan.sensor_kind == "range_azimuth_altitude") {
          EXPECT_NEAR(q[j](0), z[j](0), kNauticalMileM / 256.0 / 2.0 + 1e-9);
          EXPECT_NEAR(std::remainder(q[j](1) - z[j](1), 2.0 * std::numbers::pi), 0.0,
                      std::numbers::pi / 65536.0 + 1e-12);
          EXPECT_NEAR(q[j](2), z[j](2), 12.5 * kFootM + 1e-9);
          ++plots;
        } else {
          // 180/2^30 degrees of latitude is 2 cm; the height 6.25 ft; the ground speed 2^-14
          // NM/s and the track angle 360/2^16 degrees; the vertical rate 6.25 ft/min.
          EXPECT_NEAR(q[j](0), z[j](0), 0.05);
          EXPECT_NEAR(q[j](1), z[j](1), 0.05);
          EXPECT_NEAR(q[j](2), z[j](2), 3.125 * kFootM + 0.01);
          const double speed = std::hypot(z[j](3), z[j](4));
          const double tolerance =
              kNauticalMileM / 16384.0 / 2.0 + speed * 2.0 * std::numbers::pi / 65536.0;
          EXPECT_NEAR(q[j](3), z[j](3), tolerance);
          EXPECT_NEAR(q[j](4), z[j](4), tolerance);
          EXPECT_NEAR(q[j](5), z[j](5), 3.125 * kFootM / 60.0 + 1e-12);
          ++reports;
        }
      }
      const std::optional<Scan> twice =
          quantised_as_asterix({scan.sensor_kind, *once, scan.target}, station, scenario);
      ASSERT_TRUE(twice.has_value());
      ASSERT_EQ(twice->detections.size(), q.size());
      for (std::size_t j = 0; j < q.size(); ++j) {
        EXPECT_TRUE(same_detection(twice->detections[j], q[j]))
            << scan.sensor_kind << " detection " << j << " round " << k;
      }
      EXPECT_EQ(twice->addresses, once->addresses);
    }
  }
  EXPECT_GT(plots, 50U);
  EXPECT_GT(reports, 50U);
  EXPECT_GT(identified, 50U) << "every addressed simulated aircraft has a callsign";
}

TEST(ScanAsterix, SkipsAPlotOrReportThatCannotBeADetectionAndCountsIt) {
  asterix::RadarPlot without_level;
  without_level.range_m = 5000.0;
  std::size_t skipped = 0;
  const auto plots = scan_of_plots(7, "range_azimuth_altitude",
                                   std::span<const asterix::RadarPlot>(&without_level, 1), skipped);
  ASSERT_TRUE(plots.has_value());
  EXPECT_TRUE(plots->detections.empty());
  EXPECT_EQ(skipped, 1U);
  // A primary radar's plot needs none: range and azimuth, azimuth 0 (north) as π/2.
  const auto primary = scan_of_plots(
      3, "range_azimuth", std::span<const asterix::RadarPlot>(&without_level, 1), skipped);
  ASSERT_TRUE(primary.has_value());
  ASSERT_EQ(primary->detections.size(), 1U);
  EXPECT_NEAR(primary->detections[0](1), std::numbers::pi / 2.0, 1e-15);
  EXPECT_TRUE(primary->addresses.empty());
  EXPECT_FALSE(scan_of_plots(1, "range_azimuth_elevation", {}, skipped).has_value());

  asterix::AdsbReport without_height;
  without_height.ground_vector = asterix::GroundVector{100.0, 90.0};
  skipped = 0;
  const GeoAnchor anchor{48.3538, 11.7861, 448.0};
  const auto reports =
      scan_of_reports(9, std::span<const asterix::AdsbReport>(&without_height, 1), anchor, skipped);
  ASSERT_TRUE(reports.has_value());
  EXPECT_TRUE(reports->detections.empty());
  EXPECT_EQ(skipped, 1U);
}

// A feed file read back: the scans of a station's records, as a pcap of datagrams and as raw
// data blocks one after another, are the same — and are the quantised scans the records were
// made of, round by round.
// A report's quality indicators (I021/090) state its σ: NACp 9 bounds the 95 % horizontal
// position error by 30 m and NACv 2 the horizontal velocity's by 3 m/s, so σ per axis is each
// bound over √χ²₂(0.95); the height and vertical rate keep the station's noise (0), and so does
// a report whose categories are unknown (0). A scan of reports stating nothing states nothing.
TEST(ScanAsterix, AReportsQualityIndicatorsStateItsSigma) {
  const GeoAnchor anchor{48.3538, 11.7861, 448.0};
  asterix::AdsbReport stating;
  stating.latitude_deg = anchor.latitude_deg;
  stating.longitude_deg = anchor.longitude_deg;
  stating.geometric_height_m = 500.0;
  stating.ground_vector = asterix::GroundVector{50.0, 45.0};
  stating.quality.nacp = 9;
  stating.quality.nucr_or_nacv = 2;
  asterix::AdsbReport silent = stating;
  silent.quality.nacp = 0;
  silent.quality.nucr_or_nacv = 0;
  std::size_t skipped = 0;
  const std::vector<asterix::AdsbReport> both{stating, silent};
  const auto scan = scan_of_reports(9, both, anchor, skipped);
  ASSERT_TRUE(scan.has_value());
  ASSERT_EQ(scan->reported_std.size(), 2U);
  const Detection& stated = scan->reported_std[0];
  ASSERT_EQ(stated.size(), 6);
  EXPECT_DOUBLE_EQ(stated(0), 30.0 / 2.447746830680816);
  EXPECT_DOUBLE_EQ(stated(1), 30.0 / 2.447746830680816);
  EXPECT_EQ(stated(2), 0.0);
  EXPECT_DOUBLE_EQ(stated(3), 3.0 / 2.447746830680816);
  EXPECT_DOUBLE_EQ(stated(4), 3.0 / 2.447746830680816);
  EXPECT_EQ(stated(5), 0.0);
  EXPECT_TRUE(scan->reported_std[1].isZero());

  // As a station's R: the stated axes' variances are the stated σ², the others the station's.
  Covariance<6> station = Covariance<6>::Identity() * 100.0;
  station(0, 1) = station(1, 0) = 20.0;
  const Covariance<6> r = reported_noise<6>(station, stated);
  EXPECT_NEAR(r(0, 0), stated(0) * stated(0), 1e-12);
  EXPECT_NEAR(r(3, 3), stated(3) * stated(3), 1e-12);
  EXPECT_EQ(r(2, 2), 100.0);
  EXPECT_NEAR(r(0, 1) / std::sqrt(r(0, 0) * r(1, 1)), 0.2, 1e-15) << "the correlation kept";
  EXPECT_TRUE(reported_noise<6>(station, scan->reported_std[1]) == station);

  const std::vector<asterix::AdsbReport> none{silent};
  const auto quiet = scan_of_reports(9, none, anchor, skipped);
  ASSERT_TRUE(quiet.has_value());
  EXPECT_TRUE(quiet->reported_std.empty());

  // uam-mixed's Remote ID receivers (σ 10 m, 1 m/s) broadcast NACp 9 and NACv 2: a station fed
  // their reports takes those bounds' σ.
  const Scenario scenario = uam_mixed();
  const auto truth = build_traffic_truth(scenario).targets;
  const auto scans = simulated_scans_at(scenario, truth, 10, 0, 20);
  const SimulatedScan& remote_id = scans[8];
  ASSERT_EQ(remote_id.sensor_kind, "position_velocity");
  ASSERT_FALSE(remote_id.scan.detections.empty());
  const auto fed = quantised_as_asterix(remote_id, scenario.stations[8], scenario);
  ASSERT_TRUE(fed.has_value());
  ASSERT_EQ(fed->reported_std.size(), fed->detections.size());
  for (const Detection& s : fed->reported_std) EXPECT_TRUE(s == stated);

  // A receiver less sure of north than of east broadcasts the bound that holds on both: σ 20 m
  // north is 49 m at 95 %, NACp 8 (under 92.6 m), where east's 10 m alone would say NACp 9.
  StationConfig lopsided = scenario.stations[8];
  lopsided.sensor.noise_std(1) = 20.0;
  const ScanRecords records = scan_records(remote_id, lopsided, 0.0, scenario);
  ASSERT_EQ(records.category, asterix::kCat021);
  ASSERT_FALSE(records.records.empty());
  std::optional<asterix::EncodeError> error;
  const auto blocks =
      asterix::encode_blocks(records.category, records.records, asterix::kMaxUdpPayload, error);
  ASSERT_FALSE(error.has_value());
  asterix::Decoded decoded;
  for (const asterix::Bytes& block : blocks) asterix::decode_datagram(block, decoded);
  ASSERT_FALSE(decoded.reports.empty());
  EXPECT_EQ(decoded.reports[0].quality.nacp, 8);
  EXPECT_EQ(decoded.reports[0].quality.nucr_or_nacv, 2);
}

TEST(ReplayedScans, APcapAndARawFileOfTheSameRecordsGiveTheQuantisedScans) {
  const Scenario scenario = uam_mixed();
  const auto truth = build_traffic_truth(scenario).targets;
  constexpr int kStations = 10;
  constexpr int kFirst = 20;  // the aircraft appear over the first minute
  constexpr int kRounds = 6;
  const std::filesystem::path dir = std::filesystem::path(SKYFUSE_TEST_WORK_DIR) / "replayed_scans";
  std::filesystem::create_directories(dir);
  const auto pcap = dir / "feed.pcap";
  const auto raw = dir / "feed.ast";
  std::vector<std::vector<SimulatedScan>> rounds;
  {
    asterix::PcapWriter writer(pcap);
    std::ofstream blocks(raw, std::ios::binary);
    for (int k = kFirst; k < kFirst + kRounds; ++k) {
      rounds.push_back(simulated_scans_at(scenario, truth, kStations, 0, k));
      for (std::size_t s = 0; s < rounds.back().size(); ++s) {
        const ScanRecords records = scan_records(rounds.back()[s], scenario.stations[s],
                                                 k * scenario.time_step_s, scenario);
        if (records.category == 0 || records.records.empty()) continue;
        std::optional<asterix::EncodeError> error;
        for (const asterix::Bytes& block : asterix::encode_blocks(records.category, records.records,
                                                                  asterix::kMaxUdpPayload, error)) {
          writer.write({0, {{127, 0, 0, 7}, 8601}, {{127, 0, 0, 1}, 8600}, block});
          blocks.write(reinterpret_cast<const char*>(block.data()),
                       static_cast<std::streamsize>(block.size()));
        }
        ASSERT_FALSE(error.has_value());
      }
    }
    writer.close();
  }
  std::size_t detections = 0;
  for (const int id : {7, 9}) {  // a Mode S radar and a Remote ID receiver
    const StationConfig& station = scenario.stations[static_cast<std::size_t>(id - 1)];
    ReplayedScans from_pcap(pcap, scenario, station);
    ReplayedScans from_raw(raw, scenario, station);
    EXPECT_EQ(from_pcap.detections(), from_raw.detections());
    EXPECT_EQ(from_pcap.refusals().total(), 0U);
    EXPECT_EQ(from_raw.refusals().total(), 0U);
    for (int k = kFirst; k < kFirst + kRounds; ++k) {
      const SimulatedScan& simulated =
          rounds[static_cast<std::size_t>(k - kFirst)][static_cast<std::size_t>(id - 1)];
      const Scan expected = *quantised_as_asterix(simulated, station, scenario);
      for (ReplayedScans* replayed : {&from_pcap, &from_raw}) {
        const Scan scan = replayed->scan_at(static_cast<std::uint64_t>(k), simulated.scan.noise);
        ASSERT_EQ(scan.detections.size(), expected.detections.size()) << id << " round " << k;
        for (std::size_t j = 0; j < scan.detections.size(); ++j) {
          EXPECT_TRUE(same_detection(scan.detections[j], expected.detections[j]));
        }
        EXPECT_EQ(scan.addresses, expected.addresses);
        EXPECT_EQ(scan.station_id, id);
      }
      detections += expected.detections.size();
    }
  }
  EXPECT_GT(detections, 50U);
  // A sensor no item carries is refused by name.
  StationConfig elevation = scenario.stations[0];
  elevation.sensor.kind = "range_azimuth_elevation";
  EXPECT_THROW(ReplayedScans(pcap, scenario, elevation), std::invalid_argument);
}

}  // namespace
}  // namespace skyfuse::transport
