// The sensor parts that split the largest shards a second time (registry/sensor_parts.hpp): a
// scenario's stations reach the part that compiled their sensor, mixed stations included, and
// every slot lies in exactly one part.
#include "skyfuse/registry/sensor_parts.hpp"

#include <gtest/gtest.h>

#include "skyfuse/registry/part_info.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"

namespace skyfuse {
namespace {

TEST(SensorParts, SlotsFollowTheRegistrysOrderWithMixedStationsLast) {
  EXPECT_EQ(kSensorSlot<RangeAzimuthElevation>, 0U);
  EXPECT_EQ(kSensorSlot<PositionVelocity>, 1U);
  EXPECT_EQ(kSensorSlot<RangeDifferenceSensor>, 2U);
  EXPECT_EQ(kSensorSlot<AnySensor>, sensor_infos().size());
}

TEST(SensorParts, AScenarioReachesThePartOfItsStationsSensor) {
  Scenario scenario = load_default_scenario();
  ASSERT_GE(scenario.stations.size(), 2U);
  for (StationConfig& station : scenario.stations) station.sensor.kind = "position_velocity";
  EXPECT_EQ(sensor_slot(scenario, 2), kSensorSlot<PositionVelocity>);
  const std::size_t part =
      with_sensor_part<2>(scenario, 2, [](auto p) { return decltype(p)::value; });
  EXPECT_TRUE((in_sensor_part<PositionVelocity, 1, 2>));
  EXPECT_EQ(part, 1U);

  scenario.stations[1].sensor.kind = "range_azimuth_elevation";
  EXPECT_EQ(sensor_slot(scenario, 1), kSensorSlot<PositionVelocity>) << "only the first station";
  EXPECT_EQ(sensor_slot(scenario, 2), kSensorSlot<AnySensor>) << "two kinds: mixed";
}

TEST(SensorParts, EverySlotLiesInExactlyOnePart) {
  constexpr std::size_t kParts = 3;
  const auto parts_holding = []<template <int> class Sensor>(SensorTemplate<Sensor>) {
    return int{in_sensor_part<Sensor, 0, kParts>} + int{in_sensor_part<Sensor, 1, kParts>} +
           int{in_sensor_part<Sensor, 2, kParts>};
  };
  EXPECT_EQ(parts_holding(SensorTemplate<RangeAzimuthElevation>{}), 1);
  EXPECT_EQ(parts_holding(SensorTemplate<PositionVelocity>{}), 1);
  EXPECT_EQ(parts_holding(SensorTemplate<RangeDifferenceSensor>{}), 1);
  EXPECT_EQ(parts_holding(SensorTemplate<AnySensor>{}), 1);
}

}  // namespace
}  // namespace skyfuse
