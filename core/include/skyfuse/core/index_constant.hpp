#pragma once
/// \file
/// From a number known at run time to one known at compile time: to name the instantiation of a
/// shard (registry/filter_shards.hpp) or a sensor part (registry/sensor_parts.hpp) with it.

#include <cstddef>
#include <type_traits>
#include <utility>

namespace skyfuse {

/// Calls f(std::integral_constant<std::size_t, I>{}) for the I in [0, Count) that equals
/// `index` and returns what it returns; a value-initialised result, f not called, when `index`
/// is Count or more.
template <std::size_t Count, typename F>
auto with_index_constant(std::size_t index, F&& f) {
  using Result = decltype(f(std::integral_constant<std::size_t, 0>{}));
  Result result{};
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (void)((I == index ? (result = f(std::integral_constant<std::size_t, I>{}), true) : false) ||
           ...);
  }
  (std::make_index_sequence<Count>{});
  return result;
}

}  // namespace skyfuse
