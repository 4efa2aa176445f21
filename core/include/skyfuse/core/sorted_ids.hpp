#pragma once
/// \file
/// Stations are kept in ascending id everywhere (sums, stacking, records); this finds one.

#include <algorithm>
#include <cstddef>
#include <optional>
#include <span>
#include <vector>

namespace skyfuse {

/// Where `id` sits in the ascending `sorted_ids`, or nothing if it is not there.
inline std::optional<std::size_t> position_of(std::span<const int> sorted_ids, int id) {
  const auto it = std::lower_bound(sorted_ids.begin(), sorted_ids.end(), id);
  if (it == sorted_ids.end() || *it != id) return std::nullopt;
  return static_cast<std::size_t>(it - sorted_ids.begin());
}

/// `ids` in ascending order, the order that position_of() and every round keep.
inline std::vector<int> sorted_ascending(std::vector<int> ids) {
  std::sort(ids.begin(), ids.end());
  return ids;
}

}  // namespace skyfuse
