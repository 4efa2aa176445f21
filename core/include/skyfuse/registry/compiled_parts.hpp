#pragma once
/// \file
/// Which filter parts this build compiled the code of every configuration for: every part, or,
/// where the build was configured for some only (SKYFUSE_FILTER_PARTS, as ./quickstart demo
/// does for the EKF), those. A scenario of another part is refused when it is loaded, with the
/// way to build it.

#include <cstddef>
#include <string_view>

#include "skyfuse/registry/compiled_filter_parts.hpp"  // generated: SKYFUSE_COMPILED_FILTER_PARTS

namespace skyfuse {

/// The filter parts this build compiled, comma-separated; empty: every one.
inline constexpr std::string_view kCompiledFilterParts = SKYFUSE_COMPILED_FILTER_PARTS;

/// Whether this build compiled the code of filter part `kind`.
constexpr bool filter_part_compiled(std::string_view kind) {
  std::string_view parts = kCompiledFilterParts;
  if (parts.empty()) return true;
  while (!parts.empty()) {
    const std::size_t comma = parts.find(',');
    if (parts.substr(0, comma) == kind) return true;
    parts = comma == std::string_view::npos ? std::string_view() : parts.substr(comma + 1);
  }
  return false;
}

/// What to do when a filter part is not in this build.
inline constexpr std::string_view kHowToBuildEveryPart =
    "./quickstart demo builds the EKF only; `./quickstart test` builds every part, or configure "
    "with -DSKYFUSE_FILTER_PARTS=all and build again";

}  // namespace skyfuse
