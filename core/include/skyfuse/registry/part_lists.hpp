#pragma once
/// \file
/// Compile-time lists of motion models, sensors and filters, and the calls that turn a scenario's
/// name for a part into its type. The lists themselves are in registry.hpp.

#include <algorithm>
#include <cstddef>
#include <optional>
#include <string_view>
#include <type_traits>
#include <utility>

namespace skyfuse {

template <typename... Models>
struct ModelList {};

/// Sensors are templates over the state dimension N: Sensor<N> works on an N-state.
template <template <int> class... Sensors>
struct SensorList {};

template <typename... Models, typename F>
bool visit_model_kind_in(ModelList<Models...> /*list*/, std::string_view kind, F& f) {
  return ((Models::kKind == kind ? (f(std::type_identity<Models>{}), true) : false) || ...);
}

/// Calls f(std::type_identity<Model>{}) for the model of `List` whose kKind is `kind`; false,
/// and f not called, when there is none.
template <typename List, typename F>
bool visit_model_kind(std::string_view kind, F&& f) {
  return visit_model_kind_in(List{}, kind, f);
}

/// A sensor template as a value: `typename decltype(tag)::template For<N>` is the sensor of an
/// N-entry state.
template <template <int> class Sensor>
struct SensorTemplate {
  template <int N>
  using For = Sensor<N>;
};

template <int N, template <int> class... Sensors, typename F>
bool visit_sensor_kind_in(SensorList<Sensors...> /*list*/, std::string_view kind, F& f) {
  const auto try_one = [&]<template <int> class Sensor>(SensorTemplate<Sensor> tag) {
    if constexpr (Sensor<N>::kJacobianCols <= N) {
      if (Sensor<N>::kKind != kind) return false;
      f(tag);
      return true;
    } else {
      return false;
    }
  };
  return (try_one(SensorTemplate<Sensors>{}) || ...);
}

/// Calls f(SensorTemplate<Sensor>{}) for the sensor of `List` whose kKind is `kind` and that
/// fits an N-entry state (it reads no state entry beyond N); false, and f not called, otherwise.
template <typename List, int N, typename F>
bool visit_sensor_kind(std::string_view kind, F&& f) {
  return visit_sensor_kind_in<N>(List{}, kind, f);
}

template <typename... Filters>
struct FilterList {};

/// Whether filter part `Filter` is the one named by `kind` and, for a filter with modes, by
/// `modes` (its mode names in order).
template <typename Filter, typename ModeNames>
bool filter_part_is(std::string_view kind, const ModeNames& modes) {
  if (Filter::kKind != kind) return false;
  return Filter::kModeNames.empty() ||
         std::ranges::equal(Filter::kModeNames, modes, [](std::string_view a, const auto& b) {
           return a == std::string_view(b);
         });
}

template <typename... Filters, typename ModeNames>
std::optional<std::size_t> filter_part_index_in(FilterList<Filters...> /*list*/,
                                                std::string_view kind, const ModeNames& modes) {
  std::size_t index = 0;
  const bool found = ((filter_part_is<Filters>(kind, modes) || (++index, false)) || ...);
  return found ? std::optional(index) : std::nullopt;
}

/// The position in `List` of the filter part named by `kind` and `modes`; none if none is.
template <typename List, typename ModeNames>
std::optional<std::size_t> filter_part_index(std::string_view kind, const ModeNames& modes) {
  return filter_part_index_in(List{}, kind, modes);
}

template <std::size_t Shard, std::size_t Shards, typename... Filters, typename ModeNames,
          typename F>
bool visit_filter_part_in_shard_in(FilterList<Filters...> /*list*/, std::string_view kind,
                                   const ModeNames& modes, F& f) {
  return [&]<std::size_t... I>(std::index_sequence<I...>) {
    const auto try_part = [&]<std::size_t Index, typename Filter>() {
      if constexpr (Index % Shards == Shard) {
        if (filter_part_is<Filter>(kind, modes)) {
          f(std::type_identity<Filter>{});
          return true;
        }
      }
      return false;
    };
    return (try_part.template operator()<I, Filters>() || ...);
  }
  (std::index_sequence_for<Filters...>{});
}

/// visit_filter_part for the parts of `List` in shard `Shard` of `Shards`: those whose position
/// modulo Shards is Shard. f is compiled for those parts only, so that code compiled for every
/// part can be split over Shards translation units (registry/filter_shards.hpp).
template <typename List, std::size_t Shard, std::size_t Shards, typename ModeNames, typename F>
bool visit_filter_part_in_shard(std::string_view kind, const ModeNames& modes, F&& f) {
  return visit_filter_part_in_shard_in<Shard, Shards>(List{}, kind, modes, f);
}

/// Calls f(std::type_identity<Filter>{}) for the filter part of `List` named by `kind` and
/// `modes` (filter_part_is); false, and f not called, when there is none. The one place a
/// filter's name is compared (dispatch.hpp's visit_filter takes them from a scenario): all the
/// parts form one shard.
template <typename List, typename ModeNames, typename F>
bool visit_filter_part(std::string_view kind, const ModeNames& modes, F&& f) {
  return visit_filter_part_in_shard<List, 0, 1>(kind, modes, f);
}

}  // namespace skyfuse
