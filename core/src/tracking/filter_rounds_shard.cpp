// One aircraft's filter rounds for every sensor, compiled here once per shard of the
// configuration groups and nowhere else: a station's contribution (the increment rules'
// contribute, the IMM peer's), the peers' IMM fusion and the center's stacked update (the EKF's,
// the IMM's). The Monte Carlo's steppers, the station and center processes, paper 000's IMM
// experiment and the pictures see only their declarations and link these; before, each compiled
// the same arithmetic for every sensor again (docs/testing.md#the-largest-files).
// cmake/FilterShards.cmake compiles this file once per shard and sensor part
// (registry/sensor_parts.hpp), with SKYFUSE_SHARD and SKYFUSE_SENSOR_PART set: the default IMM's
// rounds for every sensor in one file took 1.69 GB.
#include <span>
#include <tuple>
#include <type_traits>

#include "skyfuse/registry/filter_shards.hpp"
#include "skyfuse/registry/registry.hpp"
#include "skyfuse/registry/sensor_parts.hpp"
#include "skyfuse/tracking/central_tracker_impl.hpp"
#include "skyfuse/tracking/imm_network_impl.hpp"
#include "skyfuse/tracking/increment_rules_impl.hpp"
#include "skyfuse/tracking/network_imm.hpp"

namespace skyfuse {
namespace {

// Naming each round by its address makes the compiler compile it here, and `used` keeps the
// addresses, though nothing reads them, so this object file holds every round for the linker.

// A part with an increment rule: a station's contribution, and the prior a round prepares once
// for every station where the rule has one (the unscented filter's).
template <typename Rule, int N, typename Sensor>
void keep_increment_rule() {
  [[gnu::used]] static constexpr auto kContribute = &Rule::template contribute<N, Sensor>;
  if constexpr (requires { typename Rule::template RoundPrior<N>; }) {
    using RoundPrior = typename Rule::template RoundPrior<N>;
    [[gnu::used]] static constexpr auto kPrepared = &RoundPrior::template contribute<Sensor>;
  }
}

// The EKF's center: the stacked update of stations of `Sensor` (one kind, or any mix).
template <typename Model, typename Sensor>
void keep_stacked_center() {
  [[gnu::used]] static constexpr auto kUpdate = &CentralTracker<Model, Sensor>::update_stacked;
}

// The network IMM of `Set`: its peers' fusion, and per sensor a station's contribution and the
// center's stacked update.
template <typename Set>
void keep_imm_fusion() {
  using Peer = typename NetworkImm<Set>::Peer;
  [[gnu::used]] static constexpr auto kFusion = std::tuple{&Peer::fuse_round, &Peer::fuse_total};
}
template <typename Set, template <int> class SensorOf, int N>
void keep_imm_sensor() {
  using Peer = typename NetworkImm<Set>::Peer;
  using Central = typename NetworkImm<Set>::Central;
  using StackedUpdate =
      NumericalStatus (Central::*)(std::span<const StationObservation<SensorOf<N>>>);
  [[gnu::used]] static constexpr auto kRounds =
      std::tuple{&Peer::template contribute<SensorOf, N>,
                 static_cast<StackedUpdate>(&Central::template update<SensorOf, N>)};
}

// Every round of filter part `Filter` on `Model` for the sensors of sensor part `Part` of
// `Parts` it runs on: each registered sensor the model can carry (as visit_sensor_kind offers
// them) and, where the part takes stations of different kinds, their pack. What does not depend
// on the sensor is in part 0.
template <typename Filter, typename Model, std::size_t Part, std::size_t Parts>
void keep_group_rounds() {
  constexpr int N = Model::kDim;
  // An IMM part names its modes (ImmFilterPart::ModeSet); every other part has none.
  constexpr bool kImm = !Filter::kModeNames.empty();
  if constexpr (kImm && Part == 0) {
    keep_imm_fusion<typename Filter::ModeSet>();
  }
  const auto each_sensor = [&]<template <int> class SensorOf>(SensorTemplate<SensorOf>) {
    using Sensor = SensorOf<N>;
    if constexpr (in_sensor_part<SensorOf, Part, Parts> && Sensor::kJacobianCols <= N &&
                  filter_runs_on<Filter, Model, Sensor>()) {
      if constexpr (kImm) {
        keep_imm_sensor<typename Filter::ModeSet, SensorOf, N>();
      } else if constexpr (requires { typename Filter::IncrementRule; }) {
        keep_increment_rule<typename Filter::IncrementRule, N, Sensor>();
        if constexpr (std::is_same_v<Filter, EkfFilterPart>) keep_stacked_center<Model, Sensor>();
      }
    }
  };
  [&]<template <int> class... SensorOf>(SensorList<SensorOf...>) {
    (each_sensor(SensorTemplate<SensorOf>{}), ...);
  }(Sensors{});
  if constexpr (std::is_same_v<Filter, EkfFilterPart> && in_sensor_part<AnySensor, Part, Parts> &&
                filter_runs_on<Filter, Model, AnySensor<N>>()) {
    keep_stacked_center<Model, AnySensor<N>>();
  }
}

}  // namespace

template <std::size_t Shard, std::size_t Part>
void keep_filter_rounds_in_shard() {
  for_each_group_in_shard<Shard>(
      []<typename Filter, typename Model>(std::type_identity<Filter>, std::type_identity<Model>) {
        keep_group_rounds<Filter, Model, Part, kSensorPartsOf<Shard>>();
      });
}

template void keep_filter_rounds_in_shard<SKYFUSE_SHARD, SKYFUSE_SENSOR_PART>();

}  // namespace skyfuse
