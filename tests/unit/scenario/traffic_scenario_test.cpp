// Scenarios with many aircraft: what the loader takes from `traffic:`, `detection:`,
// `tracker:` and `metrics:`, what it refuses, and the truth the traffic gives.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>

#include "skyfuse/picture/detection_prior.hpp"
#include "skyfuse/picture/registration.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/scenario/traffic_config.hpp"
#include "skyfuse/sim/picture_plan.hpp"
#include "skyfuse/sim/picture_truth.hpp"
#include "skyfuse/sim/run_plan.hpp"
#include "skyfuse/traffic/traffic_truth.hpp"

namespace skyfuse {
namespace {

const std::string kUamCity = std::string(SKYFUSE_SOURCE_DIR) + "/scenarios/uam-city.yaml";

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// `text` with one piece of it replaced; the piece must be there.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  if (at == std::string::npos) throw std::logic_error("test fixture: '" + from + "' not found");
  return text.replace(at, from.size(), to);
}

std::string uam_city_with(const std::string& from, const std::string& to) {
  return replaced(read_text(kUamCity), from, to);
}

std::string rejection(const std::string& yaml) {
  try {
    parse_scenario(yaml, "test.yaml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "accepted";
  return {};
}

TEST(TrafficScenario, LoadsUamCity) {
  const Scenario s = load_scenario_file(kUamCity);
  ASSERT_TRUE(s.has_many_targets());
  const TrafficConfig& traffic = *s.traffic;
  ASSERT_TRUE(traffic.generator);
  EXPECT_EQ(traffic.generator->aircraft, 20);
  EXPECT_EQ(s.stations.size(), 8U);
  EXPECT_DOUBLE_EQ(traffic.detection.probability, 0.9);
  EXPECT_DOUBLE_EQ(traffic.detection.clutter_per_scan, 5.0);
  EXPECT_DOUBLE_EQ(traffic.detection.field_of_view.max_range_m, 12000.0);
  EXPECT_EQ(s.tracker.management.confirm_hits, 2);
  EXPECT_EQ(s.tracker.management.confirm_window, 3);
  EXPECT_EQ(s.tracker.management.delete_misses, 5);
  EXPECT_EQ(s.tracker.initiation.min_stations, 2);
  EXPECT_DOUBLE_EQ(traffic.gospa.cutoff_m, 50.0);
}

TEST(TrafficScenario, TheGeneratorsAircraftAreAFunctionOfTheSeed) {
  const Scenario s = load_scenario_file(kUamCity);
  const TrafficTruth a = build_traffic_truth(s);
  const TrafficTruth b = build_traffic_truth(s);
  ASSERT_EQ(a.targets.size(), 20U);
  for (std::size_t t = 0; t < a.targets.size(); ++t) {
    EXPECT_EQ(a.targets[t].states, b.targets[t].states);
    EXPECT_GE(a.targets[t].first_step, 0);
    EXPECT_LE(a.targets[t].first_step, 60);
    // Flying at the generator's speeds, at its heights.
    const auto& x = a.targets[t].states.front();
    EXPECT_GE(x.segment<3>(3).norm(), 15.0 - 1e-9);
    EXPECT_LE(x.segment<3>(3).norm(), 45.0 + 1e-9);
    EXPECT_GE(x(2), 120.0);
    EXPECT_LE(x(2), 450.0);
  }
  Scenario other = s;
  other.seed += 1;
  EXPECT_NE(build_traffic_truth(other).targets[0].states.front(), a.targets[0].states.front());
}

TEST(TrafficScenario, AListedTargetAppearsAndLeavesWhenTold) {
  const std::string yaml = uam_city_with(R"(traffic:
  generator:)",
                                         R"(traffic:
  targets:
    - {initial_position_m: [0, 0, 200], velocity_mps: [20, 0, 0], appears_s: 10, leaves_s: 50}
  generator:)");
  const TrafficTruth truth = build_traffic_truth(parse_scenario(yaml, "test.yaml"));
  ASSERT_EQ(truth.targets.size(), 21U);
  const TargetTruth& listed = truth.targets.front();
  EXPECT_EQ(listed.label, "T0");
  EXPECT_FALSE(listed.present_at(9));
  EXPECT_TRUE(listed.present_at(10));
  EXPECT_TRUE(listed.present_at(50));
  EXPECT_FALSE(listed.present_at(51));
  EXPECT_NEAR((listed.at(20).head<3>() - Vector3(200, 0, 200)).norm(), 0.0, 1e-9);
}

TEST(TrafficScenario, AStationMayDetectDifferently) {
  const std::string yaml = uam_city_with(
      "{id: 2, position_m: [0.0, -5000.0, 45.0], sensor: *radar}",
      "{id: 2, position_m: [0.0, -5000.0, 45.0], sensor: *radar, detection: {probability: 0.5, "
      "azimuth_sector_deg: [90, 60]}}");
  const Scenario s = parse_scenario(yaml, "test.yaml");
  ASSERT_TRUE(s.stations[1].detection);
  EXPECT_DOUBLE_EQ(s.stations[1].detection->probability, 0.5);
  EXPECT_DOUBLE_EQ(s.stations[1].detection->clutter_per_scan, 5.0);  // the scenario's
  ASSERT_TRUE(s.stations[1].detection->field_of_view.azimuth_sector);
  EXPECT_NEAR(s.stations[1].detection->field_of_view.azimuth_sector->half_width_rad,
              60.0 * std::numbers::pi / 180.0, 1e-12);
  // A station without its own takes the scenario's, resolved by the loader once for every user.
  ASSERT_TRUE(s.stations[0].detection);
  EXPECT_DOUBLE_EQ(s.stations[0].detection->probability, s.traffic->detection.probability);
  EXPECT_FALSE(s.stations[0].detection->field_of_view.azimuth_sector);
}

// Stations of different sensor kinds share one picture (a radar beside a receiver of the
// aircraft's own position-velocity reports), except under a filter whose modes read one kind.
TEST(TrafficScenario, TakesStationsOfDifferentSensorKinds) {
  const std::string broadcast_station =
      "{id: 2, sensor: {kind: position_velocity, noise_std: [10, 10, 10, 1, 1, 1]}, "
      "detection: {clutter_per_scan: 0.0}}";
  const std::string radar_station = "{id: 2, position_m: [0.0, -5000.0, 45.0], sensor: *radar}";
  const Scenario s = parse_scenario(uam_city_with(radar_station, broadcast_station), "test.yaml");
  EXPECT_EQ(s.stations[0].sensor.kind, "range_azimuth_elevation");
  EXPECT_EQ(s.stations[1].sensor.kind, "position_velocity");
  ASSERT_TRUE(s.stations[1].detection);
  EXPECT_DOUBLE_EQ(s.stations[1].detection->clutter_per_scan, 0.0);

  std::string imm = uam_city_with(radar_station, broadcast_station);
  imm.replace(imm.find("  kind: ekf"), std::string("  kind: ekf").size(), "  kind: imm");
  imm.replace(imm.find("kind: constant_velocity_3d\n    process_noise_std: {position_m: 0.5, "
                       "velocity_mps: 2.0}"),
              std::string("kind: constant_velocity_3d\n    process_noise_std: {position_m: 0.5, "
                          "velocity_mps: 2.0}")
                  .size(),
              "kind: constant_acceleration_3d\n    process_noise_std: {position_m: 0.5, "
              "velocity_mps: 2.0, acceleration_mps2: 0.5}");
  const std::string refused = rejection(imm);
  EXPECT_NE(refused.find("filter 'imm' needs every station to have the same sensor kind"),
            std::string::npos)
      << refused;
}

// Identity: a station whose sensor reports addresses, the share of aircraft that carry one, and
// the tracker's sanity gate; each aircraft's address drawn from the seed.
TEST(TrafficScenario, TakesCooperativeSensorsAndTheShareOfAircraftWithAnAddress) {
  std::string yaml =
      uam_city_with("{id: 2, position_m: [0.0, -5000.0, 45.0], sensor: *radar}",
                    "{id: 2, sensor: {kind: position_velocity, noise_std: [10, 10, 10, 1, 1, 1]}, "
                    "detection: {clutter_per_scan: 0.0, reports_address: true}}");
  yaml = yaml.replace(yaml.find("traffic:\n"), 9, "traffic:\n  equipped_share: 0.6\n");
  yaml = yaml.replace(yaml.find("tracker:\n"), 9,
                      "tracker:\n  identity: {sanity_gate_probability: 0.99999, "
                      "merge_probability: 0.95}\n");
  const Scenario s = parse_scenario(yaml, "test.yaml");
  EXPECT_TRUE(s.stations[1].detection->reports_address);
  EXPECT_FALSE(s.stations[0].detection->reports_address);
  EXPECT_DOUBLE_EQ(s.traffic->equipped_share, 0.6);
  EXPECT_DOUBLE_EQ(s.tracker.identity.sanity_gate_probability, 0.99999);
  EXPECT_DOUBLE_EQ(s.tracker.identity.merge_probability, 0.95);
  EXPECT_DOUBLE_EQ(load_scenario_file(kUamCity).tracker.identity.merge_probability, 0.99)
      << "the default";
  for (const char* bad : {"1.0", "-0.1"}) {
    std::string refused = read_text(kUamCity);
    refused.replace(refused.find("tracker:\n"), 9,
                    std::string("tracker:\n  identity: {merge_probability: ") + bad + "}\n");
    EXPECT_NE(rejection(refused).find("merge_probability"), std::string::npos) << bad;
  }

  const TrafficTruth truth = build_traffic_truth(s);
  std::size_t equipped = 0;
  std::vector<Address> addresses;
  for (const TargetTruth& t : truth.targets) {
    if (t.address == kNoAddress) {
      EXPECT_EQ(t.identification, kNoIdentification) << "no callsign without an address";
      continue;
    }
    ++equipped;
    addresses.push_back(t.address);
    // A simulated aircraft's callsign is "SF" and its address's six hex digits.
    EXPECT_EQ(callsign_of(t.identification), fmt::format("SF{:06X}", t.address));
  }
  EXPECT_GT(equipped, 0U);
  EXPECT_LT(equipped, truth.targets.size());
  std::sort(addresses.begin(), addresses.end());
  EXPECT_EQ(std::adjacent_find(addresses.begin(), addresses.end()), addresses.end())
      << "no two aircraft share an address";
  const TrafficTruth again = build_traffic_truth(s);
  for (std::size_t t = 0; t < truth.targets.size(); ++t) {
    EXPECT_EQ(truth.targets[t].address, again.targets[t].address) << "a function of the seed";
  }

  EXPECT_NE(rejection(uam_city_with("traffic:\n", "traffic:\n  equipped_share: 1.5\n"))
                .find("must be in [0, 1]"),
            std::string::npos);
  EXPECT_NE(rejection(uam_city_with("clutter_per_scan: 5.0",
                                    "clutter_per_scan: 5.0\n  reports_address: maybe"))
                .find("expected true or false"),
            std::string::npos);
}

// What the network can see: a cooperative station sees only the aircraft with an address.
TEST(TrafficScenario, ACooperativeStationSeesOnlyTheAircraftWithAnAddress) {
  Scenario s = load_scenario_file(std::string(SKYFUSE_SOURCE_DIR) + "/scenarios/uam-mixed.yaml");
  std::erase_if(s.stations, [](const StationConfig& station) { return station.id != 9; });
  ASSERT_EQ(s.stations.size(), 1U);
  ASSERT_TRUE(s.stations[0].detection->reports_address);
  const TrafficTruth truth = build_traffic_truth(s);
  std::vector<TruthPoint> aircraft;
  aircraft_at_step(s, 1, truth.targets, 100, aircraft);
  ASSERT_EQ(aircraft.size(), 100U);
  std::size_t addressed = 0;
  for (const TruthPoint& a : aircraft) {
    EXPECT_EQ(a.addressed, truth.targets[a.target].address != kNoAddress);
    EXPECT_EQ(a.in_view, a.addressed) << "every aircraft is within the receiver's range";
    if (a.addressed) ++addressed;
  }
  EXPECT_GT(addressed, 40U);
  EXPECT_LT(addressed, 80U) << "uam-mixed equips 60 %";
}

// An ADS-B ground station that replays a recorded file's own reports: read from the shipped
// scenario, and refused by name where nothing broadcasts what it would replay.
TEST(TrafficScenario, AReceiverReplaysRecordedBroadcastsOnlyWhereThereAreSome) {
  const std::string path =
      std::string(SKYFUSE_SOURCE_DIR) + "/scenarios/recorded-airport-adsb.yaml";
  const Scenario s = load_scenario_file(path);
  ASSERT_EQ(s.stations.size(), 5U);
  EXPECT_TRUE(s.stations[4].detection->replays_broadcasts);
  EXPECT_TRUE(s.stations[4].detection->reports_address);
  EXPECT_FALSE(s.stations[0].detection->replays_broadcasts);

  const std::string text = read_text(path);
  const auto with = [&](const std::string& from, const std::string& to) {
    return replaced(text, from, to);
  };
  const std::string not_a_broadcast = rejection(
      with("sensor: {kind: position_velocity, noise_std: [20.0, 20.0, 20.0, 3.0, 3.0, 3.0]}",
           "position_m: [0.0, 0.0, 30.0]\n    sensor: *radar"));
  EXPECT_NE(not_a_broadcast.find("stations[4].detection: replays_broadcasts: a recorded broadcast "
                                 "is a position_velocity report; station's sensor is "
                                 "range_azimuth_elevation"),
            std::string::npos)
      << not_a_broadcast;
  const std::string unaddressed =
      rejection(with("reports_address: true", "reports_address: false"));
  EXPECT_NE(unaddressed.find("set reports_address: true"), std::string::npos) << unaddressed;
  const std::string generated = rejection(
      with("  recorded:\n    file: opensky-states.csv   # relative to this file; --traffic-file "
           "overrides it\n    max_staleness_s: 15.0\n",
           "  generator: {aircraft: 10}\n"));
  EXPECT_NE(generated.find("the scenario has no traffic.recorded"), std::string::npos) << generated;
}

// A station's systematic errors: read for the components its sensor measures, refused for
// others, beyond a bias's bounds, and where there is no picture.
TEST(TrafficScenario, ReadsAStationsBiasesAndRefusesWhatItCannotHave) {
  const std::string second = "{id: 2, position_m: [0.0, -5000.0, 45.0], sensor: *radar}";
  const auto with_bias = [&](const std::string& bias) {
    return uam_city_with(second,
                         "{id: 2, position_m: [0.0, -5000.0, 45.0], sensor: *radar, "
                         "bias: " +
                             bias + "}");
  };
  const Scenario s = parse_scenario(
      with_bias("{range_m: 150.0, azimuth_rad: 0.0026, elevation_rad: -0.0017, time_s: 0.5}"),
      "test.yaml");
  const SensorBias& bias = s.stations[1].detection->bias;
  EXPECT_EQ(bias.range_m, 150.0);
  EXPECT_EQ(bias.azimuth_rad, 0.0026);
  EXPECT_EQ(bias.elevation_rad, -0.0017);
  EXPECT_EQ(bias.time_s, 0.5);
  EXPECT_FALSE(s.stations[0].detection->bias.any());

  const std::string degrees = rejection(with_bias("{azimuth_rad: 0.15}"));
  EXPECT_NE(degrees.find("stations[1].bias.azimuth_rad: must be within +-0.1 rad"),
            std::string::npos)
      << degrees;
  EXPECT_NE(rejection(with_bias("{x_m: 3.0}")).find("x_m"), std::string::npos);
  const std::string receiver = rejection(
      uam_city_with(second,
                    "{id: 2, sensor: {kind: position_velocity, noise_std: [10, 10, 10, 1, 1, 1]}, "
                    "bias: {range_m: 20.0}}"));
  EXPECT_NE(receiver.find("a position_velocity sensor measures no range_m (it measures x_m, "
                          "y_m, z_m, vx_mps, vy_mps, vz_mps)"),
            std::string::npos)
      << receiver;
  const std::string one_aircraft = rejection(replaced(
      read_text(std::string(SKYFUSE_SOURCE_DIR) + "/scenarios/paper000.yaml"),
      "{id: 2, position_m: [-450.0, -450.0, 20.0], sensor: *radar}",
      "{id: 2, position_m: [-450.0, -450.0, 20.0], sensor: *radar, bias: {range_m: 5.0}}"));
  EXPECT_NE(one_aircraft.find("bias: only a scenario with 'traffic'"), std::string::npos)
      << one_aircraft;
}

// The tracker's registration: off unless named, its prior read by name, anything else refused.
TEST(TrafficScenario, ReadsTheTrackersRegistration) {
  const std::string text =
      read_text(std::string(SKYFUSE_SOURCE_DIR) + "/scenarios/registration.yaml");
  EXPECT_EQ(parse_scenario(text, "test.yaml").tracker.registration.kind, "none");
  const auto with = [&](const std::string& registration) {
    return replaced(text, "tracker:\n", "tracker:\n  registration: " + registration + "\n");
  };
  const Scenario s = parse_scenario(
      with("{kind: least_squares, prior_std: {range_m: 300.0, time_s: 0.5}}"), "test.yaml");
  EXPECT_EQ(s.tracker.registration.kind, "least_squares");
  EXPECT_TRUE(estimates_biases(s.tracker.registration));
  EXPECT_EQ(s.tracker.registration.range_std_m, 300.0);
  EXPECT_EQ(s.tracker.registration.azimuth_std_rad, 0.01);  // the default
  EXPECT_EQ(s.tracker.registration.time_std_s, 0.5);
  EXPECT_FALSE(
      estimates_biases(parse_scenario(with("{kind: none}"), "test.yaml").tracker.registration));
  EXPECT_NE(rejection(with("{kind: kalman}"))
                .find("unknown registration 'kalman'; known: none, least_squares"),
            std::string::npos);
  EXPECT_NE(rejection(with("{kind: least_squares, prior_std: {range_m: 0.0}}")).find("range_m"),
            std::string::npos);
}

// The tracker's updater: linearises at the prior unless told, relinearises the EKF's increments
// up to its bound, and is refused for a part that takes its own increments.
TEST(TrafficScenario, ReadsTheTrackersUpdater) {
  const std::string text =
      read_text(std::string(SKYFUSE_SOURCE_DIR) + "/scenarios/registration.yaml");
  EXPECT_EQ(parse_scenario(text, "test.yaml").tracker.updater.relinearisations, 0);
  const auto with = [&](const std::string& updater) {
    return replaced(text, "tracker:\n", "tracker:\n  updater: " + updater + "\n");
  };
  EXPECT_EQ(
      parse_scenario(with("{relinearisations: 2}"), "test.yaml").tracker.updater.relinearisations,
      2);
  EXPECT_NE(rejection(with("{relinearisations: 6}")).find("must be in [0, 5], got 6"),
            std::string::npos);
  EXPECT_NE(rejection(with("{relinearisations: -1}")).find("must be in [0, 5]"), std::string::npos);
  EXPECT_NE(rejection(with("{iterations: 1}")).find("iterations"), std::string::npos);
  const std::string ukf =
      rejection(replaced(with("{relinearisations: 1}"), "  kind: ekf\n", "  kind: ukf\n"));
  EXPECT_NE(ukf.find("relinearises the EKF's increments; filter 'ukf' takes its own"),
            std::string::npos)
      << ukf;
  const std::string jpda = rejection(with("{relinearisations: 1}\n  associator: jpda"));
  EXPECT_NE(jpda.find("associator 'jpda' does not yet take an updater that relinearises"),
            std::string::npos)
      << jpda;
}

TEST(TrafficScenario, RefusesWhatAPictureCannotTake) {
  EXPECT_NE(rejection(uam_city_with("traffic:",
                                    "target: {initial_position_m: [0, 0, 100], "
                                    "velocity_mps: [10, 0, 0]}\ntraffic:"))
                .find("either 'target' (one aircraft) or 'traffic'"),
            std::string::npos);
  EXPECT_NE(rejection(uam_city_with("clutter_per_scan: 5.0", "clutter_per_scan: 5000"))
                .find("exceeds the bound of 1000"),
            std::string::npos);
  EXPECT_NE(rejection(uam_city_with("aircraft: 20", "aircraft: 20000")).find("[1, 10000]"),
            std::string::npos);
  EXPECT_NE(rejection(uam_city_with("  max_range_m: 12000.0\n", "")).find("finite"),
            std::string::npos);
  EXPECT_NE(rejection(uam_city_with("confirm: [2, 3]", "confirm: [4, 3]")).find("M <= N"),
            std::string::npos);
  const std::string tdoa = rejection(uam_city_with(
      "sensor: &radar {kind: range_azimuth_elevation, noise_std: [5.0, 0.0026, 0.0026]}",
      "sensor: &radar {kind: tdoa_range_difference, noise_std: [5.0]}"));
  EXPECT_NE(tdoa.find("fixes no position"), std::string::npos) << tdoa;
}

TEST(TrafficScenario, TakesTheImmOnItsConstantAccelerationMode) {
  const Scenario s = parse_scenario(uam_city_with(R"(  kind: ekf
  motion_model:
    kind: constant_velocity_3d
    process_noise_std: {position_m: 0.5, velocity_mps: 2.0})",
                                                  R"(  kind: imm
  motion_model:
    kind: constant_acceleration_3d
    process_noise_std: {position_m: 0.5, velocity_mps: 2.0, acceleration_mps2: 0.5})"),
                                    "test.yaml");
  EXPECT_EQ(s.filter.kind, "imm");
}

// uam-city.yaml whose tracker names `tracker_lines` before its gate, and whose filter is
// replaced where given.
std::string uam_city_tracking(const std::string& tracker_lines, const std::string& filter = "") {
  std::string text =
      uam_city_with("  gate_probability: 0.9999", tracker_lines + "\n  gate_probability: 0.9999");
  const auto replace = [&](const std::string& from, const std::string& to) {
    if (to.empty()) return;
    text.replace(text.find(from), from.size(), to);
  };
  replace(R"(  kind: ekf
  motion_model:
    kind: constant_velocity_3d
    process_noise_std: {position_m: 0.5, velocity_mps: 2.0})",
          filter);
  return text;
}

TEST(TrafficScenario, NamesItsAssociatorAndRefusesOneItCannotRun) {
  EXPECT_EQ(load_scenario_file(kUamCity).tracker.association.associator, "gnn");
  const Scenario jpda = parse_scenario(uam_city_tracking("  associator: jpda"), "test.yaml");
  EXPECT_EQ(jpda.tracker.association.associator, "jpda");

  const std::string unknown = rejection(uam_city_tracking("  associator: mht"));
  EXPECT_NE(unknown.find("unknown associator 'mht'; known: gnn, jpda"), std::string::npos)
      << unknown;
  // The IMM's mode likelihoods do not add up over weighed pairs.
  const std::string imm = rejection(uam_city_tracking("  associator: jpda", R"(  kind: imm
  motion_model:
    kind: constant_acceleration_3d
    process_noise_std: {position_m: 0.5, velocity_mps: 2.0, acceleration_mps2: 0.5})"));
  EXPECT_NE(imm.find("filter 'imm' cannot fuse the weighed pairs of associator 'jpda'"),
            std::string::npos)
      << imm;
  // A given density is every station's; without one a radar's comes from its clutter and field
  // of view: 5 a scan over 12 km x 2 pi x pi / 2.
  const Scenario given = parse_scenario(
      uam_city_tracking("  associator: jpda\n  clutter_density: 1.0e-9"), "test.yaml");
  const AssociationConfig& association = given.tracker.association;
  EXPECT_EQ(association.clutter_density, 1.0e-9);
  EXPECT_EQ(detection_prior(given.traffic->detection, "range_azimuth_elevation", association)
                .clutter_density,
            1.0e-9);
  const DetectionPrior radar =
      detection_prior(jpda.traffic->detection, "range_azimuth_elevation", jpda.tracker.association);
  EXPECT_DOUBLE_EQ(radar.clutter_density,
                   5.0 / (12000.0 * 2.0 * std::numbers::pi * std::numbers::pi / 2.0));
  EXPECT_EQ(radar.detection_probability, 0.9);
  EXPECT_EQ(radar.gate_probability, 0.9999);
  // A position fix's clutter, drawn uniform in range and angles, is not uniform in x, y, z: JPDA
  // needs its density given; GNN never reads it.
  try {
    (void)detection_prior(jpda.traffic->detection, "position_velocity", jpda.tracker.association);
    ADD_FAILURE() << "a position fix's clutter density was made up";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("give tracker.clutter_density"), std::string::npos)
        << e.what();
  }
  EXPECT_NO_THROW(
      (void)detection_prior(jpda.traffic->detection, "position_velocity", AssociationConfig{}));
}

// --associator swaps the associator of a run of many aircraft and checks it again; a run of one
// aircraft refuses it.
TEST(TrafficScenario, AssociatorOverridesTheTrackersOnlyWhereItCanRun) {
  RunOverrides overrides;
  overrides.associator = "jpda";
  const PicturePlan plan = make_picture_plan(load_scenario_file(kUamCity), overrides);
  EXPECT_EQ(plan.scenario.tracker.association.associator, "jpda");
  const auto refusal = [&](auto make) -> std::string {
    try {
      make();
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "accepted";
  };
  const std::string one = refusal([&] { make_run_plan(load_default_scenario(), overrides); });
  EXPECT_NE(one.find("--associator: scenario 'paper000' has one aircraft"), std::string::npos)
      << one;
  Scenario imm = parse_scenario(uam_city_tracking("  associator: gnn", R"(  kind: imm
  motion_model:
    kind: constant_acceleration_3d
    process_noise_std: {position_m: 0.5, velocity_mps: 2.0, acceleration_mps2: 0.5})"),
                                "test.yaml");
  const std::string part = refusal([&] { make_picture_plan(imm, overrides); });
  EXPECT_NE(part.find("--associator: filter 'imm' cannot fuse"), std::string::npos) << part;
}

TEST(TrafficScenario, AOneTargetScenarioTakesNoTrackerSettings) {
  std::string text(default_scenario_yaml());
  text += "\ntracker: {confirm: [2, 3]}\n";
  EXPECT_NE(rejection(text).find("only a scenario with 'traffic'"), std::string::npos);
}

TEST(TrafficScenario, ProcessesRefuseManyAircraftWithAPointerToTheSweep) {
  try {
    make_run_plan(load_scenario_file(kUamCity), {});
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("skyfuse sweep"), std::string::npos) << e.what();
  }
}

// The scenarios of the throughput goals load as their comments say: 100 and 1 000 aircraft,
// 16 radars scanning at 10 Hz with 10 false alarms a scan.
TEST(TrafficScenario, TheMetroAndCrowdScenariosCarryTheirLoads) {
  for (const auto& [file, aircraft] :
       {std::pair<const char*, int>{"uam-metro.yaml", 100}, {"uam-crowd.yaml", 1000}}) {
    const Scenario s = load_scenario_file(std::string(SKYFUSE_SOURCE_DIR) + "/scenarios/" + file);
    ASSERT_TRUE(s.has_many_targets()) << file;
    EXPECT_EQ(s.traffic->generator->aircraft, aircraft) << file;
    EXPECT_EQ(s.stations.size(), 16U) << file;
    EXPECT_DOUBLE_EQ(s.time_step_s, 0.1) << file;
    EXPECT_DOUBLE_EQ(s.traffic->detection.clutter_per_scan, 10.0) << file;
    EXPECT_DOUBLE_EQ(s.traffic->detection.probability, 0.9) << file;
  }
}

// --aircraft sets a generated scenario's aircraft count for the run's plan, leaving the loaded
// scenario as it was; a scenario with one target or with recorded traffic refuses it.
TEST(TrafficScenario, AircraftOverridesTheGeneratorsCountOnly) {
  const Scenario city = load_scenario_file(kUamCity);
  RunOverrides overrides;
  overrides.aircraft = 7;
  const PicturePlan plan = make_picture_plan(city, overrides);
  EXPECT_EQ(plan.scenario.traffic->generator->aircraft, 7);
  EXPECT_EQ(city.traffic->generator->aircraft, 20) << "the loaded scenario is unchanged";
  EXPECT_EQ(build_traffic_truth(plan.scenario).targets.size(), 7U);

  const auto refusal = [&](const Scenario& scenario, bool picture) -> std::string {
    try {
      if (picture) {
        make_picture_plan(scenario, overrides);
      } else {
        make_run_plan(scenario, overrides);
      }
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(refusal(load_default_scenario(), false).find("--aircraft"), std::string::npos);
  const Scenario recorded =
      load_scenario_file(std::string(SKYFUSE_SOURCE_DIR) + "/scenarios/recorded-airport.yaml");
  EXPECT_NE(refusal(recorded, true).find("--aircraft"), std::string::npos);
  overrides.aircraft = 0;
  EXPECT_NE(refusal(city, true).find("--aircraft"), std::string::npos);
}

}  // namespace
}  // namespace skyfuse
