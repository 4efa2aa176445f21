#pragma once
/// \file
/// Which filter parts the station and center processes of a run with many aircraft run: every
/// part a picture runs in-process (multitarget/picture_parts.hpp) but the IMM, whose tracks hold
/// a state per mode that the picture a parted peer takes (wire::PictureState) does not carry yet.

#include <fmt/format.h>

#include <stdexcept>
#include <type_traits>

#include "skyfuse/registry/dispatch.hpp"
#include "skyfuse/scenario/scenario.hpp"

namespace skyfuse::transport {

/// Whether the processes run a picture with `filter`'s part: one whose tracks are a single
/// Gaussian.
inline bool picture_filter_over_dds(const FilterConfig& filter) {
  bool single_model = false;
  visit_filter(filter, [&]<typename Filter>(std::type_identity<Filter>) {
    single_model = Filter::kModeNames.empty();
  });
  return single_model;
}

/// Throws std::invalid_argument, saying why, if the processes do not run `scenario`'s filter
/// part in a picture yet.
inline void refuse_unless_picture_over_dds(const Scenario& scenario) {
  if (!picture_filter_over_dds(scenario.filter)) {
    throw std::invalid_argument(fmt::format(
        "scenario '{}': over DDS a run of many aircraft does not run the '{}' filter yet: a "
        "peer that parted takes another's picture, and the picture sent carries one Gaussian a "
        "track, not a state per mode (`skyfuse sweep` runs it in-process)",
        scenario.name, scenario.filter.kind));
  }
}

}  // namespace skyfuse::transport
