#include "skyfuse/scenario/scenario_loader.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "skyfuse/sim/run_plan.hpp"

namespace skyfuse {
namespace {

// The embedded default scenario with one piece of text replaced; the replaced text must exist,
// so that a change to paper000.yaml cannot silently turn a test into a no-op.
std::string default_with(const std::string& from, const std::string& to) {
  std::string text(default_scenario_yaml());
  const auto at = text.find(from);
  if (at == std::string::npos) throw std::logic_error("test fixture: '" + from + "' not found");
  return text.replace(at, from.size(), to);
}

// The embedded default scenario with every occurrence of `from` replaced (at least one).
std::string default_with_all(const std::string& from, const std::string& to) {
  std::string text(default_scenario_yaml());
  std::size_t at = text.find(from);
  if (at == std::string::npos) throw std::logic_error("test fixture: '" + from + "' not found");
  for (; at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

// The message the loader throws for `yaml`, or a failure if it accepts it.
std::string rejection(const std::string& yaml) {
  try {
    parse_scenario(yaml, "test.yaml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "scenario was accepted";
  return {};
}

TEST(ScenarioLoader, LoadsTheDefaultScenarioWithThePapersParameters) {
  const Scenario s = load_default_scenario();
  EXPECT_EQ(s.name, "paper000");
  EXPECT_DOUBLE_EQ(s.time_step_s, 0.02);
  EXPECT_EQ(s.steps, 2000);
  EXPECT_EQ(s.stations.size(), 10U);
  ASSERT_EQ(s.target.speeds_mps.size(), 2U);
  EXPECT_DOUBLE_EQ(s.target.speeds_mps[0] * 3.6, 100.0);
  EXPECT_DOUBLE_EQ(s.target.speeds_mps[1] * 3.6, 300.0);
  EXPECT_EQ(s.filter.kind, "ekf");
  EXPECT_EQ(s.filter.motion_model.kind, "constant_acceleration_3d");
  EXPECT_EQ(s.filter.motion_model.process_noise_std, Vector3(0.5, 0.1, 0.05));
  EXPECT_EQ(s.filter.initial_covariance_diag, Eigen::VectorXd::Ones(9));
  EXPECT_FALSE(s.filter.initial_state_error.has_value());
  for (const StationConfig& station : s.stations) {
    EXPECT_EQ(station.sensor.kind, "range_azimuth_elevation") << "station " << station.id;
    EXPECT_EQ(station.sensor.noise_std, Vector3(0.1, 0.01, 0.01)) << "station " << station.id;
  }
  EXPECT_DOUBLE_EQ(s.stations[0].weight, 1.0);
  EXPECT_EQ(s.noise_scale.model, NoiseScaleConfig::Model::kPaper);
  ASSERT_EQ(s.target.manoeuvres.size(), 2U);
  EXPECT_NEAR(s.target.manoeuvres[0].turn_rate_rad_s, 3.0 * std::numbers::pi / 180.0, 1e-15);
}

TEST(ScenarioLoader, RefusesAMissingField) {
  EXPECT_EQ(rejection(default_with("time_step_s: 0.02\n", "")),
            "test.yaml: (top level): missing field 'time_step_s'");
  EXPECT_EQ(rejection(default_with("    position_m: [-400.0, 1200.0, 40.0]\n", "")),
            "test.yaml: stations[0]: missing field 'position_m' (a range_azimuth_elevation sensor "
            "stands somewhere) (line 36)");
  EXPECT_EQ(rejection(default_with("    sensor: &radar", "    radar: &radar")),
            "test.yaml: stations[0].radar: unknown field (allowed: id, position_m, sensor, "
            "noise_std, weight, detection, bias) (line 38)");
}

TEST(ScenarioLoader, RefusesAWrongType) {
  EXPECT_EQ(rejection(default_with("steps: 2000", "steps: many")),
            "test.yaml: steps: expected an integer, got 'many' (line 21)");
  EXPECT_EQ(rejection(default_with("steps: 2000", "steps: 20.5")),
            "test.yaml: steps: expected an integer, got '20.5' (line 21)");
  EXPECT_EQ(rejection(default_with("time_step_s: 0.02", "time_step_s: [0.02]")),
            "test.yaml: time_step_s: expected a number, got '[0.02]' (line 20)");
  EXPECT_EQ(rejection(default_with("time_step_s: 0.02", "time_step_s: .nan")),
            "test.yaml: time_step_s: must be finite, got '.nan' (line 20)");
}

TEST(ScenarioLoader, RefusesANonPositiveVariance) {
  EXPECT_EQ(
      rejection(default_with("noise_std: [0.1, 0.01, 0.01]}", "noise_std: [0.1, 0.0, 0.01]}")),
      "test.yaml: stations[0].sensor.noise_std[1]: must be > 0, got 0.0 (line 38)");
  EXPECT_EQ(
      rejection(default_with("noise_std: [0.1, 0.01, 0.01]}", "noise_std: [-0.1, 0.01, 0.01]}")),
      "test.yaml: stations[0].sensor.noise_std[0]: must be > 0, got -0.1 (line 38)");
  EXPECT_EQ(rejection(default_with("position_m: 0.5", "position_m: 0")),
            "test.yaml: filter.motion_model.process_noise_std.position_m: must be > 0, got 0 (line "
            "60)");
  EXPECT_EQ(rejection(default_with("initial_covariance_diag: 1.0", "initial_covariance_diag: -1")),
            "test.yaml: filter.initial_covariance_diag: must be > 0, got -1 (line 61)");
  EXPECT_EQ(rejection(default_with("scale_floor: 0.1", "scale_floor: 0")),
            "test.yaml: measurement_noise.scale_floor: must be > 0, got 0 (line 54)");
}

TEST(ScenarioLoader, RefusesADuplicateStationId) {
  EXPECT_EQ(rejection(default_with("{id: 2,", "{id: 1,")),
            "test.yaml: stations[1].id: duplicate station id 1 (line 39)");
}

TEST(ScenarioLoader, RefusesAStationAtTheTargetsPosition) {
  EXPECT_EQ(rejection(default_with("position_m: [-400.0, 1200.0, 40.0]",
                                   "position_m: [-1200.0, -300.0, 450.0]")),
            "test.yaml: stations[0].position_m: [-1200, -300, 450] is 0 m from the target at step "
            "0 (t = 0.000 s, speed 100 km/h); a station must stay at least 1 m away");
}

TEST(ScenarioLoader, RefusesANonPositiveTimeStep) {
  EXPECT_EQ(rejection(default_with("time_step_s: 0.02", "time_step_s: 0")),
            "test.yaml: time_step_s: must be > 0, got 0 (line 20)");
  EXPECT_EQ(rejection(default_with("time_step_s: 0.02", "time_step_s: -0.02")),
            "test.yaml: time_step_s: must be > 0, got -0.02 (line 20)");
}

TEST(ScenarioLoader, RefusesUnknownAndMisspeltFields) {
  const std::string message = rejection(default_with("seed: 20250601", "sead: 20250601"));
  EXPECT_NE(message.find("test.yaml: sead: unknown field (allowed: name, description, seed"),
            std::string::npos)
      << message;
}

TEST(ScenarioLoader, RefusesAKeyThatIsNotAFieldName) {
  // YAML allows a list or a mapping as a key; found by the fuzzer, this once escaped the loader
  // as yaml-cpp's own exception instead of a ConfigError.
  EXPECT_EQ(rejection(default_with("seed: 20250601\n", "seed: 20250601\n? [complex, key]\n: 1\n")),
            "test.yaml: (top level): expected a field name, got '[complex, key]'");
  EXPECT_EQ(rejection(default_with("{id: 2,", "{[1, 2]: 3, id: 2,")),
            "test.yaml: stations[1]: expected a field name, got '[1, 2]' (line 39)");
}

TEST(ScenarioLoader, RefusesOverlappingManoeuvres) {
  EXPECT_EQ(rejection(default_with("start_s: 30.0", "start_s: 15.0")),
            "test.yaml: target.manoeuvres[1]: overlaps manoeuvres[0] (line 30)");
}

TEST(ScenarioLoader, RefusesTextThatIsNotYaml) {
  const std::string message = rejection("name: [unclosed");
  EXPECT_EQ(message.rfind("test.yaml: not valid YAML:", 0), 0U) << message;
}

TEST(ScenarioLoader, NamesAMissingFile) {
  try {
    load_scenario_file("/nonexistent/scenario.yaml");
    FAIL() << "missing file accepted";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/scenario.yaml: cannot open scenario file");
  }
}

TEST(ScenarioLoader, ReadsAFileFromDisk) {
  const auto path = std::filesystem::temp_directory_path() / "skyfuse_loader_test.yaml";
  std::ofstream(path) << default_with("name: paper000", "name: from_disk");
  EXPECT_EQ(load_scenario_file(path).name, "from_disk");
  std::filesystem::remove(path);
}

TEST(ScenarioLoader, AcceptsAnExplicitVelocityAndAFixedInitialError) {
  const std::string yaml =
      default_with("  heading_deg: 10.0\n  climb_deg: 0.0\n  speeds_kmh: [100, 300]\n",
                   "  velocity_mps: [30.0, 40.0, 0.0]\n");
  const Scenario s = parse_scenario(yaml.substr(0, yaml.find("  initial_state_error: sampled")) +
                                        "  initial_state_error: [1, 0, 0, 0, 0, 0, 0, 0, 0]\n",
                                    "test.yaml");
  ASSERT_EQ(s.target.speeds_mps.size(), 1U);
  EXPECT_DOUBLE_EQ(s.target.speeds_mps[0], 50.0);
  EXPECT_TRUE(s.target.direction.isApprox(Vector3(0.6, 0.8, 0.0)));
  ASSERT_TRUE(s.filter.initial_state_error.has_value());
  EXPECT_EQ((*s.filter.initial_state_error)(0), 1.0);
}

// Paper 000's files before parts were named: noise_std beside the station id, the process noise
// directly under the filter. They read as the same scenario.
TEST(ScenarioLoader, ReadsPaper000sShorthandAsTheNamedParts) {
  std::string legacy = default_with_all("sensor: *radar}", "noise_std: [0.1, 0.01, 0.01]}");
  const auto replace = [&](const std::string& from, const std::string& to) {
    const auto at = legacy.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    legacy.replace(at, from.size(), to);
  };
  replace("sensor: &radar {kind: range_azimuth_elevation, noise_std: [0.1, 0.01, 0.01]}",
          "noise_std: [0.1, 0.01, 0.01]");
  replace("  kind: ekf\n  motion_model:\n    kind: constant_acceleration_3d\n    process_noise_std",
          "  process_noise_std");
  ASSERT_EQ(legacy.find("sensor:"), std::string::npos);
  ASSERT_EQ(legacy.find("motion_model:"), std::string::npos);

  const Scenario old_form = parse_scenario(legacy, "legacy.yaml");
  const Scenario named = load_default_scenario();
  EXPECT_EQ(old_form.filter.kind, named.filter.kind);
  EXPECT_EQ(old_form.filter.motion_model.kind, named.filter.motion_model.kind);
  EXPECT_EQ(old_form.filter.motion_model.process_noise_std,
            named.filter.motion_model.process_noise_std);
  ASSERT_EQ(old_form.stations.size(), named.stations.size());
  for (std::size_t i = 0; i < named.stations.size(); ++i) {
    EXPECT_EQ(old_form.stations[i].sensor.kind, named.stations[i].sensor.kind);
    EXPECT_EQ(old_form.stations[i].sensor.noise_std, named.stations[i].sensor.noise_std);
    EXPECT_EQ(old_form.stations[i].position_m, named.stations[i].position_m);
  }
}

TEST(ScenarioLoader, RefusesTheShorthandBesideTheNamedPart) {
  EXPECT_EQ(rejection(default_with("sensor: *radar}", "sensor: *radar, noise_std: [1, 1, 1]}")),
            "test.yaml: stations[1].noise_std: give the noise inside 'sensor', not beside it "
            "(line 39)");
  EXPECT_EQ(rejection(default_with("  initial_covariance_diag: 1.0",
                                   "  process_noise_std: {position_m: 1}\n"
                                   "  initial_covariance_diag: 1.0")),
            "test.yaml: filter.process_noise_std: give the process noise inside 'motion_model', "
            "not beside it (line 61)");
}

TEST(ScenarioLoader, RefusesAnUnknownPart) {
  const std::string sensor =
      rejection(default_with("kind: range_azimuth_elevation", "kind: sonar"));
  EXPECT_EQ(sensor.rfind("test.yaml: stations[0].sensor.kind: unknown sensor kind 'sonar' "
                         "(registered: range_azimuth_elevation",
                         0),
            0U)
      << sensor;
  const std::string model =
      rejection(default_with("kind: constant_acceleration_3d", "kind: constant_jerk"));
  EXPECT_EQ(model.rfind("test.yaml: filter.motion_model.kind: unknown motion model "
                        "'constant_jerk' (registered: constant_acceleration_3d",
                        0),
            0U)
      << model;
  EXPECT_EQ(rejection(default_with("kind: ekf", "kind: particle")),
            "test.yaml: filter.kind: unknown filter 'particle' (registered: ekf, imm, ncrkf, ukf) "
            "(line 57)");
}

TEST(ScenarioLoader, RefusesFieldsThatDoNotFitThePart) {
  EXPECT_EQ(rejection(default_with("noise_std: [0.1, 0.01, 0.01]}", "noise_std: [0.1, 0.01]}")),
            "test.yaml: stations[0].sensor.noise_std: expected [range_m, azimuth_rad, "
            "elevation_rad], got '[0.1, 0.01]' (line 38)");
  EXPECT_EQ(rejection(default_with(", acceleration_mps2: 0.05}", "}")),
            "test.yaml: filter.motion_model.process_noise_std: missing field 'acceleration_mps2' "
            "(line 60)");
  EXPECT_EQ(
      rejection(default_with("acceleration_mps2: 0.05}", "acceleration_mps2: 0.05, jerk: 1}")),
      "test.yaml: filter.motion_model.process_noise_std.jerk: unknown field (allowed: "
      "position_m, velocity_mps, acceleration_mps2) (line 60)");
  EXPECT_EQ(
      rejection(default_with("initial_covariance_diag: 1.0", "initial_covariance_diag: [1, 2]")),
      "test.yaml: filter.initial_covariance_diag: expected 1 or 9 numbers, got '[1, 2]' "
      "(line 61)");
}

TEST(ScenarioLoader, ReadsTheImmsModesAndKeepsTheDefaultsItOmits) {
  const Scenario s =
      parse_scenario(default_with("  kind: ekf\n",
                                  "  kind: imm\n"
                                  "  imm:\n"
                                  "    stay_probability: 0.95\n"
                                  "    coordinated_turn: {position_m: 0.02, velocity_mps: 0.1, "
                                  "turn_rate_radps: 0.003}\n"),
                     "test.yaml");
  EXPECT_EQ(s.filter.kind, "imm");
  EXPECT_EQ(s.filter.imm.stay_probability, 0.95);
  EXPECT_EQ(s.filter.imm.coordinated_turn, (std::array<double, 3>{0.02, 0.1, 0.003}));
  EXPECT_EQ(s.filter.imm.constant_velocity, ImmConfig{}.constant_velocity);
  EXPECT_EQ(s.filter.imm.initial_turn_rate_variance, ImmConfig{}.initial_turn_rate_variance);
  EXPECT_EQ(s.filter.motion_model.kind, "constant_acceleration_3d");  // the CA mode
}

TEST(ScenarioLoader, ReadsTheImmsModeSetInItsOrder) {
  EXPECT_EQ(
      ImmConfig{}.modes,
      (std::vector<std::string>{"constant_velocity", "constant_acceleration", "coordinated_turn"}));
  const Scenario s = parse_scenario(
      default_with("  kind: ekf\n",
                   "  kind: imm\n  imm: {modes: [constant_velocity, coordinated_turn]}\n"),
      "test.yaml");
  EXPECT_EQ(s.filter.imm.modes,
            (std::vector<std::string>{"constant_velocity", "coordinated_turn"}));
  const Scenario shipped =
      load_scenario_file(SKYFUSE_SOURCE_DIR "/scenarios/paper000-imm-cv-ct.yaml");
  EXPECT_EQ(shipped.filter.imm.modes, s.filter.imm.modes);
}

TEST(ScenarioLoader, RefusesAnImmModeSetTheRegistryDoesNotCompile) {
  const std::string registered =
      "registered: [constant_velocity, constant_acceleration, coordinated_turn], "
      "[constant_velocity, coordinated_turn], [constant_velocity, constant_acceleration]";
  EXPECT_EQ(
      rejection(default_with(
          "  kind: ekf\n", "  kind: imm\n  imm: {modes: [coordinated_turn, constant_velocity]}\n")),
      "test.yaml: filter.imm.modes: no filter 'imm' is registered with modes "
      "[coordinated_turn, constant_velocity]; " +
          registered + " (line 58)");
  EXPECT_EQ(rejection(default_with("  kind: ekf\n",
                                   "  kind: imm\n  imm: {modes: [constant_velocity, singer]}\n")),
            "test.yaml: filter.imm.modes: no filter 'imm' is registered with modes "
            "[constant_velocity, singer]; " +
                registered + " (line 58)");
  EXPECT_EQ(rejection(default_with(
                "  kind: ekf\n",
                "  kind: imm\n  imm: {modes: [constant_velocity, constant_velocity]}\n")),
            "test.yaml: filter.imm.modes[1]: mode 'constant_velocity' is named twice (line 58)");
  EXPECT_EQ(rejection(default_with("  kind: ekf\n", "  kind: imm\n  imm: {modes: cv}\n")),
            "test.yaml: filter.imm.modes: expected a list of mode names (line 58)");
}

TEST(ScenarioLoader, ReadsTheNetworksExchangeAndRefusesWhatCannotRun) {
  EXPECT_EQ(
      parse_scenario(default_with("  kind: ekf\n", "  kind: ekf\n"), "test.yaml").exchange.kind,
      ExchangeConfig::Kind::kAuto);
  const std::string tree = "network: {exchange: tree, fanout: 4}\n";
  const Scenario s = parse_scenario(default_with("filter:\n", tree + "filter:\n"), "test.yaml");
  EXPECT_EQ(s.exchange.kind, ExchangeConfig::Kind::kTree);
  EXPECT_EQ(s.exchange.fanout, 4);
  EXPECT_EQ(s.exchange.round_fanout(), 4u);
  EXPECT_EQ(rejection(default_with("filter:\n", "network: {exchange: star}\nfilter:\n")),
            "test.yaml: network.exchange: expected flat, tree or auto, got 'star' (line 56)");
  EXPECT_EQ(rejection(default_with("filter:\n", "network: {fanout: 1}\nfilter:\n")),
            "test.yaml: network.fanout: must be an integer in [2, 256], got 1 (line 56)");
  EXPECT_EQ(parse_scenario(default_with("filter:\n  kind: ekf\n", tree + "filter:\n  kind: imm\n"),
                           "test.yaml")
                .exchange.kind,
            ExchangeConfig::Kind::kTree);
}

// No `network.exchange` (or `auto`): the tree from 16 stations where the filter's station
// processes take it (every registered filter's), flat below; an exchange
// asked for is kept at any size. A run's plan holds the choice, as every node makes it.
TEST(ScenarioLoader, AutoChoosesTheTreeFromSixteenStationsWhereTheStationsTakeIt) {
  const Scenario ring = load_scenario_file(SKYFUSE_SOURCE_DIR "/scenarios/ring64.yaml");
  ASSERT_EQ(ring.exchange.kind, ExchangeConfig::Kind::kAuto);
  EXPECT_EQ(chosen_exchange(ring, 15), ExchangeConfig::Kind::kFlat);
  EXPECT_EQ(chosen_exchange(ring, 16), ExchangeConfig::Kind::kTree);
  EXPECT_EQ(round_fanout_for(ring, 15), 0u);
  EXPECT_EQ(round_fanout_for(ring, 64), 8u);
  EXPECT_EQ(make_run_plan(ring, stations_and_steps(8, 10)).scenario.exchange.kind,
            ExchangeConfig::Kind::kFlat);
  EXPECT_EQ(make_run_plan(ring, stations_and_steps(16, 10)).scenario.exchange.kind,
            ExchangeConfig::Kind::kTree);
  EXPECT_EQ(make_run_plan(ring, {64, 10, {}, 0, ExchangeConfig::Kind::kFlat, {}, {}, {}})
                .scenario.exchange.kind,
            ExchangeConfig::Kind::kFlat);

  const Scenario imm = load_scenario_file(SKYFUSE_SOURCE_DIR "/scenarios/paper000-imm.yaml");
  EXPECT_EQ(chosen_exchange(imm, 15), ExchangeConfig::Kind::kFlat);
  EXPECT_EQ(chosen_exchange(imm, 64), ExchangeConfig::Kind::kTree);
  const Scenario ncrkf = load_scenario_file(SKYFUSE_SOURCE_DIR "/scenarios/paper002.yaml");
  EXPECT_EQ(chosen_exchange(ncrkf, 64), ExchangeConfig::Kind::kTree);
  EXPECT_EQ(to_string(ExchangeConfig::Kind::kAuto), "auto");
  EXPECT_EQ(parse_exchange_kind("auto"), ExchangeConfig::Kind::kAuto);
}

TEST(ScenarioLoader, ReadsTheMapAnchorAndRefusesOneOffTheGlobe) {
  const GeoAnchor fallback;
  const Scenario plain = parse_scenario(default_with("filter:\n", "filter:\n"), "test.yaml");
  EXPECT_EQ(plain.anchor.latitude_deg, fallback.latitude_deg);
  const std::string anchor = "anchor: {latitude_deg: -33.86, longitude_deg: 151.21}\n";
  const Scenario s = parse_scenario(default_with("filter:\n", anchor + "filter:\n"), "test.yaml");
  EXPECT_EQ(s.anchor.latitude_deg, -33.86);
  EXPECT_EQ(s.anchor.longitude_deg, 151.21);
  EXPECT_EQ(s.anchor.altitude_m, fallback.altitude_m);
  EXPECT_EQ(rejection(default_with("filter:\n",
                                   "anchor: {latitude_deg: 90, longitude_deg: 0}\nfilter:\n")),
            "test.yaml: anchor.latitude_deg: must be within (-89, 89) degrees, got 90 (line 56)");
  EXPECT_EQ(rejection(default_with("filter:\n", "anchor: {latitude_deg: 10}\nfilter:\n")),
            "test.yaml: anchor: missing field 'longitude_deg' (line 56)");
}

TEST(ScenarioLoader, ReadsTheAsterixDataSourceAndRefusesOnePastEightBits) {
  const Scenario plain = parse_scenario(default_with("filter:\n", "filter:\n"), "test.yaml");
  EXPECT_EQ(plain.asterix.sac, 0);
  EXPECT_EQ(plain.asterix.sic, 1);
  const Scenario s = parse_scenario(
      default_with("filter:\n", "asterix: {sac: 25, sic: 200}\nfilter:\n"), "test.yaml");
  EXPECT_EQ(s.asterix.sac, 25);
  EXPECT_EQ(s.asterix.sic, 200);
  EXPECT_EQ(rejection(default_with("filter:\n", "asterix: {sac: 256}\nfilter:\n")),
            "test.yaml: asterix.sac: must be a whole number from 0 to 255 (8 bits), got 256 "
            "(line 56)");
  EXPECT_EQ(rejection(default_with("filter:\n", "asterix: {sic: -1}\nfilter:\n")),
            "test.yaml: asterix.sic: must be a whole number from 0 to 255 (8 bits), got -1 "
            "(line 56)");
  EXPECT_EQ(rejection(default_with("filter:\n", "asterix: {sac: 1, cat: 62}\nfilter:\n")),
            "test.yaml: asterix.cat: unknown field (allowed: sac, sic) (line 56)");
}

TEST(ScenarioLoader, RefusesImmSettingsThatCannotWork) {
  EXPECT_EQ(rejection(default_with("  initial_covariance_diag: 1.0",
                                   "  imm: {stay_probability: 0.9}\n"
                                   "  initial_covariance_diag: 1.0")),
            "test.yaml: filter.imm: only a filter of kind 'imm' has modes; this one is 'ekf' "
            "(line 61)");
  EXPECT_EQ(
      rejection(default_with("  kind: ekf\n", "  kind: imm\n  imm: {stay_probability: 1.5}\n")),
      "test.yaml: filter.imm.stay_probability: must be <= 1, got 1.5 (line 58)");
  EXPECT_EQ(rejection(default_with("  kind: ekf\n",
                                   "  kind: imm\n  imm: {constant_velocity: {position_m: 1}}\n")),
            "test.yaml: filter.imm.constant_velocity: missing field 'velocity_mps' (line 58)");
  // The modes read one sensor kind at their own dimensions: a mixed network is refused.
  std::string mixed = default_with("  kind: ekf\n", "  kind: imm\n");
  const std::string radar = "{id: 2, position_m: [-450.0, -450.0, 20.0], sensor: *radar}";
  mixed.replace(mixed.find(radar), radar.size(),
                "{id: 2, sensor: {kind: position_velocity, noise_std: [1, 1, 1, 1, 1, 1]}}");
  EXPECT_EQ(rejection(mixed),
            "test.yaml: stations[1]: filter 'imm' needs every station to have the same sensor "
            "kind; station 1 has range_azimuth_elevation, station 2 has position_velocity "
            "(line 39)");
}

TEST(ScenarioLoader, ReadsPaper002sTdoaReceivers) {
  const Scenario s = load_scenario_file(SKYFUSE_SOURCE_DIR "/scenarios/paper002.yaml");
  ASSERT_EQ(s.stations.size(), 3U);
  EXPECT_EQ(s.stations[0].sensor.kind, "tdoa_range_difference");
  EXPECT_EQ(s.stations[0].sensor.noise_std, Eigen::VectorXd::Constant(1, 0.4));
  EXPECT_EQ(s.stations[2].position_m, Vector3(0.0, 200.0, 0.0));
  EXPECT_EQ(s.steps, 5000);
  EXPECT_EQ(
      rejection(
          default_with("sensor: &radar {kind: range_azimuth_elevation, noise_std: [0.1, "
                       "0.01, 0.01]}",
                       "sensor: &radar {kind: tdoa_range_difference, noise_std: [0.1, 0.2]}")),
      "test.yaml: stations[0].sensor.noise_std: expected [range_difference_m], got '[0.1, 0.2]' "
      "(line 38)");
  // A horizontal receiver on a 3-D model reads its first two entries (paper002-ekf.yaml).
  EXPECT_NO_THROW(parse_scenario(
      default_with("sensor: &radar {kind: range_azimuth_elevation, noise_std: [0.1, 0.01, 0.01]}",
                   "sensor: &radar {kind: tdoa_range_difference, noise_std: [0.1]}"),
      "test.yaml"));
}

// A multilateration group stands at its reference receiver and lists its five others.
TEST(ScenarioLoader, ReadsAMultilaterationGroupsReceivers) {
  const std::string radar =
      "sensor: &radar {kind: range_azimuth_elevation, noise_std: [0.1, 0.01, 0.01]}";
  const std::string group =
      "sensor: &radar {kind: multilateration, noise_std: [5, 5, 5, 5, 5], receivers_m: "
      "[[1000, 0, 10], [0, 1000, 20], [-1000, 0, 30], [0, -1000, 40], [700, 700, 50]]}";
  const Scenario s = parse_scenario(default_with(radar, group), "test.yaml");
  EXPECT_EQ(s.stations[0].sensor.kind, "multilateration");
  ASSERT_EQ(s.stations[0].sensor.receivers_m.size(), 5U);
  EXPECT_EQ(s.stations[0].sensor.receivers_m[4], Vector3(700.0, 700.0, 50.0));

  std::string four = group;
  four.replace(four.find(", [700, 700, 50]"), 16, "");
  EXPECT_EQ(rejection(default_with(radar, four)),
            "test.yaml: stations[0].sensor.receivers_m: a multilateration sensor has 5 receivers "
            "beside the station's position; got 4 (line 38)");
  std::string none = group;
  none.erase(none.find(", receivers_m"));
  none += "}";
  EXPECT_EQ(rejection(default_with(radar, none)),
            "test.yaml: stations[0].sensor: missing field 'receivers_m' (line 38)");
  EXPECT_EQ(rejection(default_with(
                radar,
                "sensor: &radar {kind: range_azimuth_elevation, noise_std: [0.1, 0.01, "
                "0.01], receivers_m: [[1, 2, 3]]}")),
            "test.yaml: stations[0].sensor.receivers_m: a range_azimuth_elevation sensor has one "
            "receiver, at the station; remove it (line 38)");
}

// A 2-D radar measures no height: it names the heights it assumes, and only it does.
TEST(ScenarioLoader, ReadsTheHeightsA2dRadarAssumes) {
  const std::string radar =
      "sensor: &radar {kind: range_azimuth_elevation, noise_std: [0.1, 0.01, 0.01]}";
  const std::string two_d =
      "sensor: &radar {kind: range_azimuth, noise_std: [20, 0.002], height_band_m: [100, 500]}";
  const Scenario s = parse_scenario(default_with(radar, two_d), "test.yaml");
  EXPECT_EQ(s.stations[0].sensor.kind, "range_azimuth");
  ASSERT_TRUE(s.stations[0].sensor.height_band_m.has_value());
  EXPECT_EQ(s.stations[0].sensor.height_band_m->low_m, 100.0);
  EXPECT_EQ(s.stations[0].sensor.height_band_m->high_m, 500.0);

  std::string none = two_d;
  none.erase(none.find(", height_band_m"));
  none += "}";
  EXPECT_EQ(rejection(default_with(radar, none)),
            "test.yaml: stations[0].sensor: a range_azimuth sensor measures no height: give the "
            "heights it assumes, height_band_m: [low_m, high_m] (line 38)");
  std::string upside_down = two_d;
  upside_down.replace(upside_down.find("[100, 500]"), 10, "[500, 100]");
  const std::string refused = rejection(default_with(radar, upside_down));
  EXPECT_NE(refused.find("test.yaml: stations[0].sensor.height_band_m: expected [low_m, high_m] "
                         "with low below high"),
            std::string::npos)
      << refused;
  EXPECT_EQ(rejection(default_with(
                radar,
                "sensor: &radar {kind: range_azimuth_elevation, noise_std: [0.1, 0.01, "
                "0.01], height_band_m: [0, 100]}")),
            "test.yaml: stations[0].sensor.height_band_m: a range_azimuth_elevation sensor "
            "assumes no heights; remove it (line 38)");
}

TEST(ScenarioLoader, TheNcrkfNeedsItsModelAndTdoaReceivers) {
  const Scenario s = load_scenario_file(SKYFUSE_SOURCE_DIR "/scenarios/paper002.yaml");
  EXPECT_EQ(s.filter.kind, "ncrkf");
  EXPECT_EQ(s.filter.motion_model.kind, "tdoa_relative_constant_acceleration");
  EXPECT_EQ(rejection(default_with("  kind: ekf\n", "  kind: ncrkf\n")),
            "test.yaml: filter.motion_model.kind: filter 'ncrkf' runs on "
            "tdoa_relative_constant_acceleration, not 'constant_acceleration_3d' (line 59)");
  std::string radars = default_with("  kind: ekf\n", "  kind: ncrkf\n");
  const std::string model =
      "kind: constant_acceleration_3d\n"
      "    process_noise_std: {position_m: 0.5, velocity_mps: 0.1, "
      "acceleration_mps2: 0.05}";
  ASSERT_NE(radars.find(model), std::string::npos);
  radars.replace(radars.find(model), model.size(),
                 "kind: tdoa_relative_constant_acceleration\n"
                 "    process_noise_std: {acceleration_mps2: 0.1}");
  EXPECT_EQ(rejection(radars),
            "test.yaml: stations[0]: filter 'ncrkf' needs tdoa_range_difference receivers; "
            "station 1 has range_azimuth_elevation (line 36)");
  // The EKF runs on either model, with the sensors that read a position it keeps: a radar
  // reads nothing meaningful from paper 002's [dx, dy, d_t1, ...] (nor is it compiled).
  std::string ekf = radars;
  ekf.replace(ekf.find("  kind: ncrkf\n"), 14, "  kind: ekf\n");
  EXPECT_EQ(rejection(ekf),
            "test.yaml: stations[0]: a range_azimuth_elevation sensor reads a 3-D position; motion "
            "model tdoa_relative_constant_acceleration keeps a 2-D one (line 36)");
}

}  // namespace
}  // namespace skyfuse
