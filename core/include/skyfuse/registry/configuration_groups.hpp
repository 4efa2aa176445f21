#pragma once
/// \file
/// The registry's configuration groups: each filter part on each motion model it runs on,
/// numbered in the registry's order (FilterParts, and for each part MotionModels). Code compiled
/// for every configuration is split into shards by group (filter_shards.hpp), since what a
/// configuration costs to compile is mostly what its part and model share, not its sensor.

#include <cstddef>
#include <optional>
#include <type_traits>

#include "skyfuse/registry/registry.hpp"

namespace skyfuse {

namespace detail {

// Numbers the groups of FilterParts x MotionModels: (Filter, Model) the group's number, or
// (void, void) how many there are.
template <typename Filter, typename Model, typename... Filters, typename... Models>
constexpr std::optional<std::size_t> configuration_group_in(FilterList<Filters...> /*parts*/,
                                                            ModelList<Models...> /*models*/) {
  std::size_t next = 0;
  std::optional<std::size_t> found;
  const auto count_part = [&]<typename Part>(std::type_identity<Part>) {
    const auto count_pair = [&]<typename M>(std::type_identity<M>) {
      if constexpr (filter_runs_on_model<Part, M>()) {
        if (std::is_same_v<Part, Filter> && std::is_same_v<M, Model>) found = next;
        ++next;
      }
    };
    (count_pair(std::type_identity<Models>{}), ...);
  };
  (count_part(std::type_identity<Filters>{}), ...);
  return std::is_void_v<Filter> ? std::optional(next) : found;
}

}  // namespace detail

/// The number of the group of filter part `Filter` on motion model `Model`; none if the part
/// does not run on that model.
template <typename Filter, typename Model>
inline constexpr std::optional<std::size_t> kConfigurationGroup =
    detail::configuration_group_in<Filter, Model>(FilterParts{}, MotionModels{});

/// How many configuration groups the registry has: the default number of shards.
inline constexpr std::size_t kConfigurationGroups =
    *detail::configuration_group_in<void, void>(FilterParts{}, MotionModels{});

}  // namespace skyfuse
