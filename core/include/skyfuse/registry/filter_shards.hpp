#pragma once
/// \file
/// Code compiled for every registered configuration (a station's sensing and rounds, the
/// center's rounds, the Monte Carlo's steppers, the in-process picture) makes the largest
/// translation units of the build. It is split into shards by configuration group: a filter
/// part on one motion model it runs on, numbered in the registry's order (FilterParts, and for
/// each part MotionModels). Which shard holds a group is cmake/FilterShards.cmake's choice
/// (SKYFUSE_SHARD_GROUPS: groups on one motion model share a shard where that compiles in less
/// and stays small, the others have one each); with another shard count S, or for a group beyond
/// those it lists, shard s of S holds the groups whose number modulo S is s. A shard compiles
/// again only the headers the groups share (the DDS side of the processes is compiled once,
/// apart; docs/testing.md#the-largest-files).
///
/// The code is written once, as a function template over the shard defined in a header:
///
///     template <std::size_t Shard> int run_in_shard(args);  // calls visit_group_in_shard<Shard>
///
/// One source file includes that header and instantiates it for its shard:
///
///     template int run_in_shard<SKYFUSE_SHARD>(args);
///
/// and cmake/FilterShards.cmake compiles that file once per shard. The caller, which sees only
/// the declaration, goes through with_filter_shard(filter, ...).

#include <cstddef>
#include <iterator>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "skyfuse/core/index_constant.hpp"
#include "skyfuse/registry/compiled_parts.hpp"
#include "skyfuse/registry/configuration_groups.hpp"
#include "skyfuse/registry/dispatch.hpp"
#include "skyfuse/registry/shard_layout.hpp"  // generated: SKYFUSE_SHARD_OF_GROUP

#if !defined(SKYFUSE_FILTER_SHARDS) || !defined(SKYFUSE_SENSOR_PARTS)
#error "SKYFUSE_FILTER_SHARDS is unset: add the sharded source with skyfuse_filter_shards()"
#endif

namespace skyfuse {

/// The number of shards; set by cmake/FilterShards.cmake.
inline constexpr std::size_t kFilterShards = SKYFUSE_FILTER_SHARDS;

namespace detail {
// The shard of each group that cmake/FilterShards.cmake placed, then an end mark.
inline constexpr std::size_t kShardOfGroup[] = {SKYFUSE_SHARD_OF_GROUP kFilterShards};
}  // namespace detail

/// The shard that compiles configuration group `group`.
constexpr std::size_t shard_of_group(std::size_t group) {
  constexpr std::size_t kPlaced = std::size(detail::kShardOfGroup) - 1;
  return group < kPlaced ? detail::kShardOfGroup[group] : group % kFilterShards;
}

/// Whether shard `Shard` compiles the group of filter part `Filter` on `Model`: a registered
/// group of a part in this build whose shard is `Shard`.
template <typename Filter, typename Model, std::size_t Shard>
constexpr bool in_shard() {
  constexpr auto group = kConfigurationGroup<Filter, Model>;
  if constexpr (group.has_value()) {
    return shard_of_group(*group) == Shard && filter_part_compiled(Filter::kKind);
  } else {
    return false;
  }
}

namespace detail {
template <std::size_t Shard, typename F, typename... Filters, typename... Models>
constexpr void for_each_group_in(FilterList<Filters...> /*parts*/, ModelList<Models...> /*models*/,
                                 F& f) {
  const auto each_part = [&]<typename Filter>(std::type_identity<Filter> part) {
    const auto each_model = [&]<typename Model>(std::type_identity<Model> model) {
      if constexpr (in_shard<Filter, Model, Shard>()) f(part, model);
    };
    (each_model(std::type_identity<Models>{}), ...);
  };
  (each_part(std::type_identity<Filters>{}), ...);
}
}  // namespace detail

/// Calls f(std::type_identity<Filter>{}, std::type_identity<Model>{}) for every group of shard
/// `Shard`, at compile time: what a shard compiles code for whatever the run (the tables and
/// filter rounds that other files only link).
template <std::size_t Shard, typename F>
constexpr void for_each_group_in_shard(F&& f) {
  static_assert(Shard < kFilterShards);
  detail::for_each_group_in<Shard>(FilterParts{}, MotionModels{}, f);
}

/// Calls f(std::type_identity<Filter>{}, std::type_identity<Model>{}) for the filter part that
/// runs `filter` and its motion model, compiled for the groups of shard `Shard` only. The
/// caller chose the shard by with_filter_shard, so a group in another shard, like a part that
/// does not run on the model, is a programming error: std::logic_error.
template <std::size_t Shard, typename F>
void visit_group_in_shard(const FilterConfig& filter, F&& f) {
  static_assert(Shard < kFilterShards);
  bool ran = false;
  visit_filter(filter, [&]<typename Filter>(std::type_identity<Filter> part) {
    visit_model_kind<MotionModels>(filter.motion_model.kind,
                                   [&]<typename Model>(std::type_identity<Model> model) {
                                     if constexpr (in_shard<Filter, Model, Shard>()) {
                                       f(part, model);
                                       ran = true;
                                     }
                                   });
  });
  if (!ran) {
    throw std::logic_error("filter part '" + filter.kind + "' on motion model '" +
                           filter.motion_model.kind + "' is not in shard " + std::to_string(Shard));
  }
}

/// Calls f(std::integral_constant<std::size_t, S>{}), S the shard that holds the group of the
/// filter part running `filter` on its motion model, and returns what it returns: the shard as
/// a constant, to name a shard's instantiation with. The loader has checked that a part runs
/// `filter` on that model, so none is a programming error and throws std::logic_error.
template <typename F>
auto with_filter_shard(const FilterConfig& filter, F&& f) {
  std::optional<std::size_t> group;
  visit_filter(filter, [&]<typename Filter>(std::type_identity<Filter>) {
    visit_model_kind<MotionModels>(filter.motion_model.kind,
                                   [&]<typename Model>(std::type_identity<Model>) {
                                     group = kConfigurationGroup<Filter, Model>;
                                   });
  });
  if (!group) {
    throw std::logic_error("no registered filter part '" + filter.kind + "' on motion model '" +
                           filter.motion_model.kind + "'");
  }
  if (!filter_part_compiled(filter.kind)) {  // the loader refuses such a scenario first
    throw std::invalid_argument("filter part '" + filter.kind +
                                "' is not in this build: " + std::string(kHowToBuildEveryPart));
  }
  return with_index_constant<kFilterShards>(shard_of_group(*group), std::forward<F>(f));
}

}  // namespace skyfuse
