#include "skyfuse/traffic/scan_simulation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <variant>
#include <vector>

#include "skyfuse/models/position_velocity.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/scenario/measurement_simulation.hpp"

namespace skyfuse {
namespace {

using Sensor = RangeAzimuthElevation<kKinematicsDim>;

const Vector3 kSite(0.0, 0.0, 10.0);

Covariance<3> radar_noise() {
  Covariance<3> noise = Covariance<3>::Zero();
  noise.diagonal() << 25.0, 1e-6, 1e-6;
  return noise;
}

// Whether two lists of detections are the same, bit for bit.
bool same_detections(const std::vector<Detection>& a, const std::vector<Detection>& b) {
  return std::equal(a.begin(), a.end(), b.begin(), b.end(), same_detection);
}

// Targets hovering at the given positions for `steps` steps.
std::vector<TargetTruth> hovering(const std::vector<Vector3>& positions, int steps) {
  std::vector<TargetTruth> truths;
  for (const Vector3& p : positions) {
    Vector<kKinematicsDim> x = Vector<kKinematicsDim>::Zero();
    x.head<3>() = p;
    truths.push_back(
        {"T", 0, std::vector<Vector<kKinematicsDim>>(static_cast<std::size_t>(steps), x)});
  }
  return truths;
}

TEST(ScanSimulation, OneTargetAlwaysSeenWithoutClutterIsTodaysMeasurement) {
  const auto truths = hovering({{3000.0, 2000.0, 500.0}}, 5);
  const Sensor sensor(kSite);
  for (int k = 0; k < 5; ++k) {
    const Scan scan =
        simulate_scan(4, sensor, kSite, radar_noise(), DetectionConfig{}, truths, k, 9, 2);
    ASSERT_EQ(scan.detections.size(), 1U);
    const Detection today = simulate_measurement(sensor, truths[0].at(k), radar_noise(), 9, 2, 4,
                                                 static_cast<std::uint64_t>(k));
    EXPECT_TRUE(same_detection(scan.detections[0], today));
  }
}

TEST(ScanSimulation, DetectsWithItsProbabilityOnlyInsideTheFieldOfView) {
  // Target 0 in view; target 1 beyond the range; target 2 below the minimum elevation.
  const auto truths =
      hovering({{3000.0, 0.0, 500.0}, {30000.0, 0.0, 500.0}, {5000.0, 0.0, -100.0}}, 4000);
  DetectionConfig config;
  config.probability = 0.7;
  config.field_of_view.max_range_m = 20000.0;
  config.field_of_view.min_elevation_rad = 0.0;
  const Sensor sensor(kSite);
  int detected = 0;
  for (int k = 0; k < 4000; ++k) {
    ScanOrigins origins;
    const auto scan =
        simulate_scan(1, sensor, kSite, radar_noise(), config, truths, k, 5, 0, &origins);
    for (const int o : origins.target) EXPECT_EQ(o, 0);
    detected += static_cast<int>(scan.detections.size());
    EXPECT_EQ(static_cast<int>(scan.detections.size()) + static_cast<int>(origins.missed), 1);
  }
  // Binomial(4000, 0.7): sd 29; 5 sd either side.
  EXPECT_NEAR(detected, 2800, 145);
}

TEST(ScanSimulation, ClutterHasItsPoissonMeanAndStaysInTheFieldOfView) {
  DetectionConfig config;
  config.field_of_view.max_range_m = 10000.0;
  config.field_of_view.min_elevation_rad = 0.05;
  config.field_of_view.azimuth_sector = AzimuthSector{1.0, 0.5};
  config.clutter_per_scan = 12.0;
  const Sensor sensor(kSite);
  std::size_t total = 0;
  constexpr int kScans = 2000;
  for (int k = 0; k < kScans; ++k) {
    const auto scan = simulate_scan(1, sensor, kSite, radar_noise(), config, {}, k, 5, 0);
    total += scan.detections.size();
    for (const auto& z : scan.detections) {
      EXPECT_LE(z(0), 10000.0);
      EXPECT_GE(z(2), 0.05 - 1e-12);
      EXPECT_LE(std::abs(z(1) - 1.0), 0.5 + 1e-12);
    }
  }
  // Poisson(12) over 2000 scans: mean 12, sd of the mean 0.077; 5 sd.
  EXPECT_NEAR(static_cast<double>(total) / kScans, 12.0, 0.39);
}

TEST(ScanSimulation, APositionVelocitySensorsFalseAlarmsMoveWithinTheBound) {
  DetectionConfig config;
  config.field_of_view.max_range_m = 5000.0;
  config.clutter_per_scan = 20.0;
  config.clutter_max_speed_mps = 40.0;
  const PositionVelocity<kKinematicsDim> sensor;
  double fastest = 0.0;
  for (int k = 0; k < 50; ++k) {
    const auto scan =
        simulate_scan(1, sensor, kSite, 4.0 * Covariance<6>::Identity(), config, {}, k, 5, 0);
    for (const auto& z : scan.detections) {
      for (int i = 3; i < 6; ++i) {
        EXPECT_LE(std::abs(z(i)), 40.0);
        fastest = std::max(fastest, std::abs(z(i)));
      }
    }
  }
  EXPECT_GT(fastest, 30.0);  // spread over the bound, not all zero
}

TEST(ScanSimulation, TheOrderSaysNothingOfTheOrigin) {
  const auto truths =
      hovering({{1000, 0, 300}, {2000, 0, 300}, {3000, 0, 300}, {4000, 0, 300}}, 200);
  DetectionConfig config;
  config.field_of_view.max_range_m = 20000.0;
  config.clutter_per_scan = 2.0;
  const Sensor sensor(kSite);
  std::set<std::vector<int>> orders;
  int first_is_target_zero = 0;
  for (int k = 0; k < 200; ++k) {
    ScanOrigins origins;
    simulate_scan(1, sensor, kSite, radar_noise(), config, truths, k, 5, 0, &origins);
    orders.insert(origins.target);
    first_is_target_zero += origins.target.front() == 0 ? 1 : 0;
  }
  EXPECT_GT(orders.size(), 150U);
  EXPECT_LT(first_is_target_zero, 100);  // about 1 in 5 with ~6 detections a scan
}

TEST(ScanSimulation, AReceiverOfRecordedBroadcastsHearsEachAsSentAndNothingBetween) {
  auto truths = hovering({{1000, 0, 300}, {2000, 500, 300}, {-800, 900, 200}}, 6);
  // Aircraft 0 broadcast at steps 1 and 4, aircraft 1 at step 4; aircraft 2 has no address.
  const auto report = [](int step, double east) {
    HeardBroadcast heard;
    heard.step = step;
    heard.position_velocity << east, 10.0, 300.0, 40.0, -2.0, 0.5;
    return heard;
  };
  truths[0].address = 0x3c6444;
  truths[0].broadcasts = {report(1, 1001.0), report(4, 1003.5)};
  truths[1].address = 0x4b1801;
  truths[1].broadcasts = {report(4, 2002.0)};
  truths[2].broadcasts = {report(4, -790.0)};
  DetectionConfig config;
  config.reports_address = true;
  config.replays_broadcasts = true;
  const PositionVelocity<kKinematicsDim> receiver;
  const Covariance<6> noise = 100.0 * Covariance<6>::Identity();
  for (int k = 0; k < 6; ++k) {
    ScanOrigins origins;
    const Scan scan = simulate_scan(7, receiver, kSite, noise, config, truths, k, 5, 0, &origins);
    ASSERT_EQ(scan.addresses.size(), scan.detections.size());
    const std::size_t expected = k == 1 ? 1U : k == 4 ? 2U : 0U;
    ASSERT_EQ(scan.detections.size(), expected) << "step " << k;
    EXPECT_EQ(origins.missed, 2U - expected) << "the addressed aircraft that sent nothing";
    for (std::size_t i = 0; i < scan.detections.size(); ++i) {
      const int from = origins.target[i];
      ASSERT_NE(from, 2) << "an aircraft without an address is not heard";
      // Exactly what it sent: no noise drawn on a real report.
      EXPECT_TRUE(same_detection(
          scan.detections[i],
          truths[static_cast<std::size_t>(from)].broadcast_at(k)->position_velocity));
      EXPECT_EQ(scan.addresses[i], truths[static_cast<std::size_t>(from)].address);
    }
  }
}

// A cooperative sensor lists each detection's identification with its address, through the
// shuffle: an aircraft's own, a false alarm's none; a scan none of whose detections has one
// lists none. The detections and addresses are those of the same scan without identifications.
TEST(ScanSimulation, ACooperativeSensorListsEachDetectionsIdentificationWithItsAddress) {
  auto truths = hovering({{1000, 0, 300}, {2000, 500, 300}, {-800, 900, 200}}, 40);
  truths[0].address = 0x3c6444;
  truths[0].identification = *identification_of("DLH4AB");
  truths[1].address = 0x4b1801;  // addressed, no callsign
  truths[2].address = 0xF00002;
  truths[2].identification = *identification_of("SFF00002");
  DetectionConfig config;
  config.reports_address = true;
  config.probability = 0.8;
  config.clutter_per_scan = 1.5;
  config.field_of_view.max_range_m = 20000.0;
  const Sensor sensor(kSite);
  auto anonymous = truths;
  for (TargetTruth& t : anonymous) t.identification = kNoIdentification;
  std::size_t identified = 0;
  for (int k = 0; k < 40; ++k) {
    ScanOrigins origins;
    const Scan scan =
        simulate_scan(3, sensor, kSite, radar_noise(), config, truths, k, 5, 0, &origins);
    const Scan plain = simulate_scan(3, sensor, kSite, radar_noise(), config, anonymous, k, 5, 0);
    EXPECT_TRUE(same_detections(scan.detections, plain.detections)) << "step " << k;
    EXPECT_EQ(scan.addresses, plain.addresses) << "step " << k;
    EXPECT_TRUE(plain.identifications.empty());
    if (scan.identifications.empty()) continue;
    ASSERT_EQ(scan.identifications.size(), scan.detections.size());
    for (std::size_t i = 0; i < scan.detections.size(); ++i) {
      const int from = origins.target[i];
      const Identification expected =
          from < 0 ? kNoIdentification : truths[static_cast<std::size_t>(from)].identification;
      EXPECT_EQ(scan.identifications[i], expected) << "step " << k << ", detection " << i;
      identified += expected != kNoIdentification ? 1U : 0U;
    }
  }
  EXPECT_GT(identified, 40U) << "about 2 x 0.8 x 40 identified detections";
}

// A biased radar: every detection of an aircraft is the unbiased one plus the station's
// offsets, drawn with the same noise; its clock's offset is the aircraft where it is that much
// later.
TEST(ScanSimulation, ABiasedStationOffsetsEachDetectionAndItsClockMovesTheAircraft) {
  std::vector<TargetTruth> truths = hovering({{3000, 2000, 500}, {-4000, 1500, 300}}, 3);
  for (TargetTruth& t : truths) {
    for (auto& x : t.states) x.segment<3>(3) << 40.0, -10.0, 1.0;
  }
  DetectionConfig plain;
  plain.field_of_view.max_range_m = 20000.0;
  DetectionConfig biased = plain;
  biased.bias = {.range_m = 150.0, .azimuth_rad = 0.0026, .elevation_rad = 0.0017};
  const Sensor sensor(kSite);
  ScanOrigins order;
  const Scan seen = simulate_scan(3, sensor, kSite, radar_noise(), plain, truths, 1, 5, 0, &order);
  const Scan off = simulate_scan(3, sensor, kSite, radar_noise(), biased, truths, 1, 5, 0);
  ASSERT_EQ(seen.detections.size(), 2U);
  ASSERT_EQ(off.detections.size(), 2U);
  for (std::size_t i = 0; i < 2; ++i) {
    const Detection difference = off.detections[i] - seen.detections[i];
    EXPECT_NEAR(difference(0), 150.0, 1e-9);
    EXPECT_NEAR(difference(1), 0.0026, 1e-12);
    EXPECT_NEAR(difference(2), 0.0017, 1e-12);
  }

  DetectionConfig late = plain;
  late.bias.time_s = 2.0;
  std::vector<TargetTruth> moved = truths;
  for (TargetTruth& t : moved) {
    for (auto& x : t.states) x = kinematics_after(x, 2.0);
  }
  const Scan clock = simulate_scan(3, sensor, kSite, radar_noise(), late, truths, 1, 5, 0);
  const Scan where = simulate_scan(3, sensor, kSite, radar_noise(), plain, moved, 1, 5, 0);
  EXPECT_TRUE(same_detections(clock.detections, where.detections));
  EXPECT_FALSE(same_detections(clock.detections, seen.detections));
}

// Half the targets seen, three false alarms a scan, within 20 km.
DetectionConfig half_seen_with_clutter() {
  DetectionConfig config;
  config.probability = 0.5;
  config.field_of_view.max_range_m = 20000.0;
  config.clutter_per_scan = 3.0;
  return config;
}

TEST(ScanSimulation, TheSameKeyGivesTheSameScan) {
  const auto truths = hovering({{1000, 0, 300}, {2000, 500, 300}}, 3);
  const DetectionConfig config = half_seen_with_clutter();
  const Sensor sensor(kSite);
  const auto a = simulate_scan(2, sensor, kSite, radar_noise(), config, truths, 2, 5, 1);
  const auto b = simulate_scan(2, sensor, kSite, radar_noise(), config, truths, 2, 5, 1);
  const auto other_run = simulate_scan(2, sensor, kSite, radar_noise(), config, truths, 2, 5, 2);
  EXPECT_TRUE(same_detections(a.detections, b.detections));
  EXPECT_FALSE(same_detections(a.detections, other_run.detections));
}

TEST(ScanSimulation, AStationsSensorAsAVariantGivesItsTypedScan) {
  const auto truths = hovering({{1000, 0, 300}, {2000, 500, 300}}, 3);
  const DetectionConfig config = half_seen_with_clutter();
  const Sensor sensor(kSite);
  const std::variant<PositionVelocity<kKinematicsDim>, Sensor> either = sensor;
  const Scan typed = simulate_scan(2, sensor, kSite, radar_noise(), config, truths, 2, 5, 1);
  const Scan visited =
      simulate_scan(2, either, kSite, DetectionNoise(radar_noise()), config, truths, 2, 5, 1);
  ASSERT_FALSE(typed.detections.empty());
  EXPECT_EQ(visited.station_id, typed.station_id);
  EXPECT_TRUE(visited.noise == typed.noise);
  for (const Detection& z : visited.detections) EXPECT_EQ(z.size(), 3);
  EXPECT_TRUE(same_detections(visited.detections, typed.detections));
}

TEST(Poisson, MeanAndVarianceForSmallAndLargeMeans) {
  for (const double mean : {0.5, 7.0, 75.0}) {
    CounterRng rng({1, 2, 3, 4, NoiseStream::kClutter});
    constexpr int kDraws = 20000;
    double sum = 0.0;
    double squares = 0.0;
    for (int i = 0; i < kDraws; ++i) {
      const double n = draw_poisson(mean, rng);
      sum += n;
      squares += n * n;
    }
    const double m = sum / kDraws;
    const double variance = squares / kDraws - m * m;
    EXPECT_NEAR(m, mean, 5.0 * std::sqrt(mean / kDraws)) << mean;
    EXPECT_NEAR(variance / mean, 1.0, 0.06) << mean;
  }
}

}  // namespace
}  // namespace skyfuse
