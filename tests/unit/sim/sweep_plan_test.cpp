// A sweep's kind is its plan's (sim/sweep_plan.hpp): decided by the scenario, with the overrides
// each kind takes, and those it does not take refused by name.
#include "skyfuse/sim/sweep_plan.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <variant>

#include "skyfuse/scenario/scenario_loader.hpp"

namespace skyfuse {
namespace {

const std::string kUamCity = std::string(SKYFUSE_SOURCE_DIR) + "/scenarios/uam-city.yaml";

std::string refusal(const Scenario& scenario, const SweepOverrides& overrides) {
  try {
    (void)make_sweep_plan(scenario, overrides);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "accepted";
}

TEST(SweepPlan, TheScenarioDecidesTheKindOnce) {
  SweepOverrides overrides;
  overrides.seed = 99;
  overrides.steps = 12;
  const SweepPlan one = make_sweep_plan(load_default_scenario(), overrides);
  ASSERT_TRUE(std::holds_alternative<OneAircraftSweep>(one));
  const auto& aircraft = std::get<OneAircraftSweep>(one);
  EXPECT_EQ(aircraft.scenario.seed, 99U);
  EXPECT_EQ(aircraft.scenario.steps, 12);
  EXPECT_EQ(aircraft.max_stations, static_cast<int>(aircraft.scenario.stations.size()));

  overrides.max_stations = 2;
  overrides.associator = "jpda";
  const SweepPlan many = make_sweep_plan(load_scenario_file(kUamCity), overrides);
  ASSERT_TRUE(std::holds_alternative<PictureSweep>(many));
  const auto& picture = std::get<PictureSweep>(many);
  EXPECT_EQ(picture.stations, 2);
  EXPECT_EQ(picture.scenario.tracker.association.associator, "jpda");
  EXPECT_EQ(picture.scenario.steps, 12);
}

TEST(SweepPlan, OnlyStationsKeepsThoseIdsInTheScenariosOrder) {
  SweepOverrides overrides;
  overrides.only_stations = {3, 1};
  const auto plan = std::get<OneAircraftSweep>(make_sweep_plan(load_default_scenario(), overrides));
  ASSERT_EQ(plan.scenario.stations.size(), 2U);
  EXPECT_EQ(plan.scenario.stations[0].id, 1);
  EXPECT_EQ(plan.scenario.stations[1].id, 3);
  EXPECT_EQ(plan.max_stations, 2);
}

TEST(SweepPlan, RefusesWhatItsKindDoesNotTakeByName) {
  SweepOverrides traffic;
  traffic.traffic_file = "flights.csv";
  EXPECT_NE(refusal(load_default_scenario(), traffic)
                .find("--traffic-file: scenario 'paper000' has one target"),
            std::string::npos);
  SweepOverrides associator;
  associator.associator = "gnn";
  EXPECT_NE(refusal(load_default_scenario(), associator).find("--associator"), std::string::npos);
  SweepOverrides too_many;
  too_many.max_stations = 99;
  EXPECT_NE(refusal(load_default_scenario(), too_many).find("--max-stations: 99 exceeds"),
            std::string::npos);
  SweepOverrides unknown;
  unknown.only_stations = {42};
  EXPECT_NE(refusal(load_default_scenario(), unknown).find("--only-stations"), std::string::npos);
}

}  // namespace
}  // namespace skyfuse
