#pragma once
/// \file
/// Compile-time lists of motion models, sensors and filters, and the calls that turn a scenario's
/// name for a part into its type. The lists themselves are in registry.hpp.

#include <algorithm>
#include <string_view>
#include <type_traits>

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

template <typename... Filters, typename ModeNames, typename F>
bool visit_filter_part_in(FilterList<Filters...> /*list*/, std::string_view kind,
                          const ModeNames& modes, F& f) {
  const auto try_part = [&]<typename Filter>(std::type_identity<Filter> part) {
    if (!filter_part_is<Filter>(kind, modes)) return false;
    f(part);
    return true;
  };
  return (try_part(std::type_identity<Filters>{}) || ...);
}

/// Calls f(std::type_identity<Filter>{}) for the filter part of `List` named by `kind` and
/// `modes` (filter_part_is); false, and f not called, when there is none. The one place a
/// filter's name is compared (dispatch.hpp's visit_filter takes them from a scenario).
template <typename List, typename ModeNames, typename F>
bool visit_filter_part(std::string_view kind, const ModeNames& modes, F&& f) {
  return visit_filter_part_in(List{}, kind, modes, f);
}

}  // namespace skyfuse
