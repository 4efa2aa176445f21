#pragma once
// The step a forged sample names for its fault, from the step k the harness ticked: one rule for
// the rogue's increments, partial sums and picture scans.

#include <cstdint>

#include "skyfuse/validation/drop_kind.hpp"

namespace skyfuse::rogue {

/// How far ahead a future step is: far enough that a rogue that wakes late on a loaded machine
/// still names a step no receiver has reached. At 5 steps, under the full suite's load, one node
/// of a picture run (158 rounds/s) counted the three future scans as duplicates or stale.
inline constexpr std::uint32_t kFarAhead = 1000;

/// k + 1 for an impersonation (in every receiver's window whether it has closed step k yet or
/// not, but not once it has closed k + 1 as well: the kind that depends on timing, so sent
/// first), k - 1 for a stale step, k + kFarAhead for a future one, k for every other fault.
constexpr std::uint32_t fault_step(DropKind kind, std::uint32_t k) {
  switch (kind) {
    case DropKind::kDuplicate:
      return k + 1;
    case DropKind::kStaleStep:
      return k - 1;
    case DropKind::kFutureStep:
      return k + kFarAhead;
    default:
      return k;
  }
}

}  // namespace skyfuse::rogue
