#pragma once
/// \file
/// Which filter part, motion model and sensor a picture runs, as types: the peers' and the
/// center's track filters (track_filters.hpp) of the scenario's filter part on its model, with
/// stations of its sensor kind. The in-process picture (sim/picture_run.hpp) and the station and
/// center processes pick them by the same rule, so that they run the same arithmetic.

#include <cstddef>
#include <type_traits>

#include "skyfuse/multitarget/fixes_position.hpp"
#include "skyfuse/multitarget/track_filters.hpp"
#include "skyfuse/registry/filter_shards.hpp"
#include "skyfuse/registry/make_parts.hpp"
#include "skyfuse/registry/registry.hpp"
#include "skyfuse/registry/sensor_parts.hpp"
#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/tracking/increment_rules.hpp"

namespace skyfuse {

/// The peers' and the center's track filters of filter part `Filter` on `Model`, with stations
/// of `SensorOf`: a part with an increment rule by that rule (the EKF's center stacks, another
/// part's fuses its own increments), the IMM by its network form.
template <typename Filter, typename Model, template <int> class SensorOf>
struct PictureParts {
  using Rule = typename Filter::IncrementRule;
  using Sensor = SensorOf<Model::kDim>;
  using Peer = PeerModelTracks<Model, Rule>;
  using Center =
      std::conditional_t<std::is_same_v<Filter, EkfFilterPart>, CenterStackedTracks<Model, Sensor>,
                         CenterIncrementTracks<Model, Sensor, Rule>>;
  static Peer peer(const Scenario& s) {
    return Peer(make_motion_model<Model>(s), s.filter.initial_covariance_diag);
  }
  static Center center(const Scenario& s) {
    return Center(make_motion_model<Model>(s), s.filter.initial_covariance_diag);
  }
};
template <typename Set, typename Model, template <int> class SensorOf>
struct PictureParts<ImmFilterPart<Set>, Model, SensorOf> {
  using Sensor = SensorOf<KinematicState::kDim>;
  using Peer = PeerImmTracks<Set>;
  using Center = CenterImmTracks<Set, Sensor>;
  static Peer peer(const Scenario& s) { return Peer(s); }
  static Center center(const Scenario& s) { return Center(s); }
};

/// Calls f(std::type_identity<PictureParts<...>>{}) for `scenario`'s filter part on its motion
/// model and its stations' sensor, if that group lies in shard `Shard` and the sensor in sensor
/// part `Part` of `Parts` (a node process: 0 of 1, every sensor), and a picture runs them: a part
/// with an increment rule or the IMM, a sensor one detection of which fixes a position. Returns
/// whether it called f.
template <std::size_t Shard, std::size_t Part, std::size_t Parts, typename F>
bool visit_picture_parts_in_shard(const Scenario& scenario, F&& f) {
  bool called = false;
  visit_group_in_shard<Shard>(
      scenario.filter,
      [&]<typename Filter, typename Model>(std::type_identity<Filter>, std::type_identity<Model>) {
        constexpr bool kIncrements = requires {
          typename Filter::IncrementRule;
        };
        constexpr bool kImm = !Filter::kModeNames.empty();
        if constexpr (kIncrements || kImm) {
          constexpr int kDim = kImm ? KinematicState::kDim : Model::kDim;
          visit_sensor_kind<Sensors, kDim>(
              scenario.stations.front().sensor.kind,
              [&]<template <int> class SensorOf>(SensorTemplate<SensorOf>) {
                using Sensor = SensorOf<kDim>;
                if constexpr (in_sensor_part<SensorOf, Part, Parts> && FixesPosition<Sensor> &&
                              filter_runs_on<Filter, Model, Sensor>()) {
                  f(std::type_identity<PictureParts<Filter, Model, SensorOf>>{});
                  called = true;
                }
              });
        }
      });
  return called;
}

}  // namespace skyfuse
