#pragma once
/// \file
/// Code compiled for every registered filter part, on every model and sensor it runs on (a
/// station's sensing and rounds, the center's rounds, the Monte Carlo's steppers), makes the
/// largest translation units of the build. It is split into shards by filter part: shard s of S
/// holds the parts whose position in FilterParts modulo S is s. A shard compiles again only the
/// headers the parts share (the DDS side of the processes is compiled once, apart), so S is the
/// number of parts by default (cmake/FilterShards.cmake; docs/testing.md#build).
///
/// The code is written once, as a function template over the shard defined in a header:
///
///     template <std::size_t Shard> int run_in_shard(args);  // calls visit_filter_in_shard<Shard>
///
/// One source file includes that header and instantiates it for its shard:
///
///     template int run_in_shard<SKYFUSE_SHARD>(args);
///
/// and cmake/FilterShards.cmake compiles that file once per shard. The caller, which sees only
/// the declaration, goes through with_filter_shard(filter, ...).

#include <cstddef>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "skyfuse/registry/dispatch.hpp"

#ifndef SKYFUSE_FILTER_SHARDS
#error "SKYFUSE_FILTER_SHARDS is unset: add the sharded source with skyfuse_filter_shards()"
#endif

namespace skyfuse {

/// The number of shards; set by cmake/FilterShards.cmake.
inline constexpr std::size_t kFilterShards = SKYFUSE_FILTER_SHARDS;

/// visit_filter for the filter parts of shard `Shard`: calls f(std::type_identity<Filter>{}) for
/// the part that runs `filter`, compiled for this shard's parts only. The caller chose the shard
/// by with_filter_shard, so a part in another shard is a programming error: std::logic_error.
template <std::size_t Shard, typename F>
void visit_filter_in_shard(const FilterConfig& filter, F&& f) {
  static_assert(Shard < kFilterShards);
  if (!visit_filter_part_in_shard<FilterParts, Shard, kFilterShards>(filter.kind, filter.imm.modes,
                                                                     f)) {
    throw std::logic_error("filter part '" + filter.kind + "' is not in shard " +
                           std::to_string(Shard));
  }
}

/// Calls f(std::integral_constant<std::size_t, S>{}), S the shard that holds the filter part
/// running `filter`, and returns what it returns: the shard as a constant, to name a shard's
/// instantiation with. The loader has checked that a part runs `filter`, so none is a
/// programming error and throws std::logic_error.
template <typename F>
auto with_filter_shard(const FilterConfig& filter, F&& f) {
  const auto index = filter_part_index<FilterParts>(filter.kind, filter.imm.modes);
  if (!index) {
    throw std::logic_error("no registered filter part '" + filter.kind + "' with these modes");
  }
  const std::size_t shard = *index % kFilterShards;
  using Result = decltype(f(std::integral_constant<std::size_t, 0>{}));
  Result result{};
  [&]<std::size_t... S>(std::index_sequence<S...>) {
    ((S == shard ? (result = f(std::integral_constant<std::size_t, S>{}), true) : false) || ...);
  }
  (std::make_index_sequence<kFilterShards>{});
  return result;
}

}  // namespace skyfuse
