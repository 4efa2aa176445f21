// The in-process picture of the shipped scenarios: every peer's picture bit-identical every
// round, the center's associations the same and its states within 1e-9, and a picture worth
// having — on uam-city.yaml and on recorded-airport.yaml flown on a file of 60 aircraft written
// here in OpenSky's state-vector format.

#include "skyfuse/sim/picture_run.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "skyfuse/scenario/associator_choice.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/traffic/geodesy.hpp"
#include "skyfuse/traffic/traffic_truth.hpp"
#include "support/opensky_states.hpp"

namespace skyfuse {
namespace {

const std::string kScenarios = std::string(SKYFUSE_SOURCE_DIR) + "/scenarios/";

void expect_guarantees(const PictureRunResult& run) {
  EXPECT_TRUE(run.peers_identical) << "first divergent step " << run.first_divergent_step;
  EXPECT_EQ(run.association_flips, 0U);
  EXPECT_LT(run.max_state_gap, 1e-9);
  EXPECT_GT(run.associations, 0U);
}

TEST(PictureRun, UamCityKeepsOnePictureAndTracksEveryAircraft) {
  Scenario scenario = load_scenario_file(kScenarios + "uam-city.yaml");
  scenario.steps = 150;
  const TrafficTruth truth = build_traffic_truth(scenario);
  const PictureRunResult run = run_picture(scenario, truth.targets, 8, 0);
  expect_guarantees(run);
  EXPECT_GT(run.false_alarms, 8U * 150U * 4U);  // about 5 a scan per radar
  EXPECT_EQ(run.score.aircraft_detected, 20U);
  EXPECT_EQ(run.score.aircraft_confirmed, 20U);
  EXPECT_GE(run.score.completeness, 0.95);
  EXPECT_LE(run.score.spuriousness, 0.05);
  EXPECT_LT(run.score.mean_time_to_confirm_s, 5.0);
}

// Every sensor in one picture (uam-mixed.yaml): six primary radars, then two Mode S radars, two
// Remote ID receivers and a multilateration group that report the 60 % of vehicles with an
// address. The mix keeps the guarantees, tracks the aircraft better than the radars alone (its
// first six stations), and holds one track per aircraft with an address.
TEST(PictureRun, UamMixedTracksBetterThanItsRadarsAloneWithOneTrackPerAddress) {
  Scenario scenario = load_scenario_file(kScenarios + "uam-mixed.yaml");
  scenario.steps = 100;
  const TrafficTruth truth = build_traffic_truth(scenario);
  ASSERT_EQ(scenario.stations.size(), 11U);
  const PictureRunResult mixed = run_picture(scenario, truth.targets, 11, 0);
  expect_guarantees(mixed);
  const PictureRunResult radars = run_picture(scenario, truth.targets, 6, 0);
  expect_guarantees(radars);
  EXPECT_LT(mixed.score.gospa_mean, 0.9 * radars.score.gospa_mean);
  EXPECT_EQ(mixed.score.duplicate_track_steps_addressed, 0U);
  EXPECT_EQ(mixed.score.aircraft_confirmed, 100U);
  // One confirmed track per aircraft at the end, and (but for the sanity gate's 1e-6) no
  // honest report refused.
  EXPECT_EQ(mixed.confirmed_at_end, 100U);
  EXPECT_LE(mixed.refused_addresses, 1U);
}

// A multilateration group alone (uam-mixed's station 11): each reply's time differences fix a
// position, so one reply starts the track of its address, and the group's five differences
// update it — every aircraft with an address tracked, one track each, the guarantees kept. (Its
// receivers on the ground fix heights poorly: alone, about half the track-steps lie beyond
// GOSPA's 50 m cut-off, docs/picture.md, "Multilateration".)
TEST(PictureRun, AMultilaterationGroupAloneTracksEveryAircraftWithAnAddress) {
  Scenario scenario = load_scenario_file(kScenarios + "uam-mixed.yaml");
  scenario.steps = 100;
  std::erase_if(scenario.stations, [](const StationConfig& s) { return s.id != 11; });
  ASSERT_EQ(scenario.stations.size(), 1U);
  ASSERT_EQ(scenario.stations[0].sensor.kind, "multilateration");
  const TrafficTruth truth = build_traffic_truth(scenario);
  std::size_t addressed = 0;
  for (const TargetTruth& t : truth.targets) addressed += t.address != kNoAddress ? 1 : 0;
  const PictureRunResult run = run_picture(scenario, truth.targets, 1, 0);
  expect_guarantees(run);
  EXPECT_EQ(run.confirmed_at_end, addressed);
  EXPECT_EQ(run.score.duplicate_track_steps_addressed, 0U);
  EXPECT_EQ(run.false_alarms, 0U);
}

// Biased radars (registration.yaml) with the registration on: every peer learns each station's
// biases from the same published pairs and corrects its detections alike, so the picture keeps
// its guarantees, and it is much nearer the aligned radars' than the biased one is.
TEST(PictureRun, RegisteredBiasedRadarsKeepOnePictureAndTrackBetter) {
  Scenario scenario = load_scenario_file(kScenarios + "registration.yaml");
  scenario.steps = 100;
  const TrafficTruth truth = build_traffic_truth(scenario);
  const PictureRunResult biased = run_picture(scenario, truth.targets, 4, 0);
  scenario.tracker.registration.kind = "least_squares";
  const PictureRunResult registered = run_picture(scenario, truth.targets, 4, 0);
  expect_guarantees(registered);
  EXPECT_LT(registered.score.gospa_mean, 0.7 * biased.score.gospa_mean)
      << "biased " << biased.score.gospa_mean << " m, registered " << registered.score.gospa_mean
      << " m";
}

TEST(PictureRun, FewerStationsKeepTheGuaranteesToo) {
  Scenario scenario = load_scenario_file(kScenarios + "uam-city.yaml");
  scenario.steps = 60;
  const TrafficTruth truth = build_traffic_truth(scenario);
  expect_guarantees(run_picture(scenario, truth.targets, 3, 1));
}

TEST(PictureRun, TheUnscentedFilterKeepsOnePictureToo) {
  Scenario scenario = load_scenario_file(kScenarios + "uam-city.yaml");
  scenario.steps = 60;
  scenario.filter.kind = "ukf";
  const TrafficTruth truth = build_traffic_truth(scenario);
  const PictureRunResult run = run_picture(scenario, truth.targets, 8, 0);
  expect_guarantees(run);
  EXPECT_GE(run.score.aircraft_confirmed, 15U);
}

TEST(PictureRun, TheImmKeepsOnePictureToo) {
  Scenario scenario = load_scenario_file(kScenarios + "uam-city.yaml");
  scenario.steps = 60;
  scenario.filter.kind = "imm";
  scenario.filter.motion_model.kind = "constant_acceleration_3d";
  scenario.filter.motion_model.process_noise_std = Vector3(0.5, 2.0, 1.0);
  scenario.filter.initial_covariance_diag = Vector<9>::Constant(100.0);
  const TrafficTruth truth = build_traffic_truth(scenario);
  const PictureRunResult run = run_picture(scenario, truth.targets, 8, 0);
  expect_guarantees(run);
  EXPECT_EQ(run.nees_dof, 6);
  EXPECT_GE(run.score.aircraft_confirmed, 15U);
}

// JPDA on crossing aircraft in 50 false alarms a scan per radar: each station's association
// probabilities, computed by every peer from the same inputs, keep one picture, and the center's
// weighed stacked update stays within 1e-9 of the peers' weighed sums.
TEST(PictureRun, JpdaKeepsOnePictureOfCrossingAircraftInDenseClutter) {
  Scenario scenario = load_scenario_file(kScenarios + "uam-crossing.yaml");
  scenario.steps = 90;  // through the crossings at 60 s
  set_associator(scenario, "jpda", "test");
  const TrafficTruth truth = build_traffic_truth(scenario);
  const PictureRunResult run = run_picture(scenario, truth.targets, 4, 0);
  expect_guarantees(run);
  EXPECT_GT(run.false_alarms, 4U * 90U * 40U);
  EXPECT_EQ(run.score.aircraft_confirmed, 8U);
}

TEST(PictureRun, JpdaWithTheUnscentedFilterKeepsOnePictureToo) {
  Scenario scenario = load_scenario_file(kScenarios + "uam-crossing.yaml");
  scenario.steps = 40;
  scenario.filter.kind = "ukf";
  set_associator(scenario, "jpda", "test");
  const TrafficTruth truth = build_traffic_truth(scenario);
  expect_guarantees(run_picture(scenario, truth.targets, 4, 0));
}

// Under the test's own name: ctest runs the tests of this file in parallel processes, and two
// writing one file tore its rows (CI, stop 69).
std::filesystem::path write_traffic_file(const GeoAnchor& anchor, double start, int minutes) {
  const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path path =
      std::filesystem::path(::testing::TempDir()) /
      fmt::format("skyfuse_{}_{}_states.csv", test->test_suite_name(), test->name());
  test::write_opensky_states(path, anchor, start, minutes);
  return path;
}

TEST(PictureRun, RecordedAirportTrafficOfSixtyAircraft) {
  Scenario scenario = load_scenario_file(kScenarios + "recorded-airport.yaml");
  scenario.steps = 100;  // 400 s of 4 s scans
  const double start = 1700000000.0;
  const auto file = write_traffic_file(scenario.anchor, start, 7);
  const TrafficTruth truth = build_traffic_truth(scenario, file.string());
  ASSERT_EQ(truth.targets.size(), 60U);
  ASSERT_TRUE(truth.recorded);
  EXPECT_EQ(truth.recorded->rows, 60U * 43U);
  const PictureRunResult run = run_picture(scenario, truth.targets, 4, 0);
  expect_guarantees(run);
  EXPECT_GE(run.score.aircraft_confirmed, 55U);
  EXPECT_GE(run.score.completeness, 0.9);
}

// The same file's rows replayed as the aircraft's own ADS-B reports by a fifth station
// (recorded-airport-adsb.yaml): each aircraft heard only at the steps after a report, about
// two scans in five here (a row every 10 s, 4 s scans). The broadcasts start a track for each
// address, the radars' tracks take it, and the picture keeps every guarantee.
TEST(PictureRun, RecordedBroadcastsJoinTheAirportsRadars) {
  Scenario scenario = load_scenario_file(kScenarios + "recorded-airport-adsb.yaml");
  scenario.steps = 100;
  const auto file = write_traffic_file(scenario.anchor, 1700000000.0, 7);
  const TrafficTruth truth = build_traffic_truth(scenario, file.string());
  ASSERT_EQ(truth.targets.size(), 60U);
  std::size_t heard = 0;
  for (const TargetTruth& aircraft : truth.targets) heard += aircraft.broadcasts.size();
  EXPECT_NEAR(static_cast<double>(heard) / (60.0 * 101.0), 0.4, 0.02);
  ASSERT_EQ(scenario.stations.size(), 5U);
  const PictureRunResult mixed = run_picture(scenario, truth.targets, 5, 0);
  expect_guarantees(mixed);
  const PictureRunResult radars = run_picture(scenario, truth.targets, 4, 0);
  EXPECT_EQ(mixed.score.aircraft_confirmed, 60U);
  EXPECT_EQ(mixed.confirmed_at_end, 60U) << "one track per aircraft";
  EXPECT_EQ(mixed.score.duplicate_track_steps_addressed, 0U);
  EXPECT_EQ(mixed.refused_addresses, 0U);
  EXPECT_LT(mixed.score.gospa_mean, radars.score.gospa_mean)
      << "radars alone " << radars.score.gospa_mean << " m, with the broadcasts "
      << mixed.score.gospa_mean << " m";
}

}  // namespace
}  // namespace skyfuse
