#pragma once
/// \file
/// A second split of sharded code (filter_shards.hpp), by the stations' sensor, for the
/// sources that run both the peers and the center for every sensor (the Monte Carlo's steppers,
/// the center's rounds, core's filter rounds; a picture's sensors are values): they made the
/// largest files, the IMM's
/// up to 1.66 GB. Such a source is compiled once per shard and sensor part: part p of P holds the
/// sensor slots whose number modulo P is p, a slot being a registered sensor's place in `Sensors`
/// or, after them, the mixed stations' AnySensor.
///
///     template <std::size_t Shard, std::size_t Part> R run_in_shard(args);
///     // in the shard file, for the sensor template SensorOf the scenario's stations have:
///     if constexpr (in_sensor_part<SensorOf, Part, kSensorPartsOf<Shard>>) { ... }
///
/// cmake/FilterShards.cmake (`BY_SENSOR`) compiles that file once per shard and part, P being
/// kSensorPartsOf<Shard>: under GCC, 2 for the shards whose files were above 1.5 GB with 1;
/// otherwise 1 (each part compiles again what the sensors share), or more where
/// SKYFUSE_SENSOR_PARTS asks; and the caller goes through
/// with_sensor_part<kSensorPartsOf<Shard>>(scenario, stations, ...).

#include <cstddef>
#include <string_view>
#include <type_traits>
#include <utility>

#include "skyfuse/core/index_constant.hpp"
#include "skyfuse/registry/registry.hpp"
#include "skyfuse/registry/shard_layout.hpp"  // generated: SKYFUSE_SENSOR_PARTS_BY_SHARD
#include "skyfuse/scenario/scenario.hpp"

namespace skyfuse {

/// The sensor parts of each shard, as cmake/FilterShards.cmake compiles them.
inline constexpr std::size_t kSensorPartsByShard[] = {SKYFUSE_SENSOR_PARTS_BY_SHARD};
/// The sensor parts of shard `Shard`.
template <std::size_t Shard>
inline constexpr std::size_t kSensorPartsOf = kSensorPartsByShard[Shard];

/// The slot of the first `stations` stations' sensor: the place of their common sensor kind in
/// `Sensors`, or the number of registered sensors when they differ (AnySensor).
std::size_t sensor_slot(const Scenario& scenario, int stations);

namespace detail {

// Any state size will do: a sensor's kind does not depend on it (part_info.cpp).
inline constexpr int kSlotStateDim = 64;

template <template <int> class Sensor, template <int> class... Sensors>
constexpr std::size_t sensor_slot_in(SensorList<Sensors...> /*list*/) {
  std::size_t slot = 0;
  bool found = false;
  const auto look = [&]<template <int> class Candidate>(SensorTemplate<Candidate>) {
    if (found) return;
    if (std::is_same_v<Sensor<kSlotStateDim>, Candidate<kSlotStateDim>>) {
      found = true;
    } else {
      ++slot;
    }
  };
  (look(SensorTemplate<Sensors>{}), ...);
  return slot;  // past the registered ones: AnySensor
}

}  // namespace detail

/// The slot of sensor template `Sensor` (see sensor_slot).
template <template <int> class Sensor>
inline constexpr std::size_t kSensorSlot = detail::sensor_slot_in<Sensor>(Sensors{});

/// Whether sensor part `Part` of `Parts` compiles the code for sensor template `Sensor`.
template <template <int> class Sensor, std::size_t Part, std::size_t Parts>
inline constexpr bool in_sensor_part = kSensorSlot<Sensor> % Parts == Part;

/// Calls f(std::integral_constant<std::size_t, P>{}), P the sensor part of `Parts` that holds
/// the first `stations` stations' sensor, and returns what it returns.
template <std::size_t Parts, typename F>
auto with_sensor_part(const Scenario& scenario, int stations, F&& f) {
  static_assert(Parts >= 1);
  return with_index_constant<Parts>(sensor_slot(scenario, stations) % Parts, std::forward<F>(f));
}

}  // namespace skyfuse
