#pragma once
/// \file
/// CentralTracker::update_stacked (central_tracker.hpp declares it). Include this file to run
/// a center with sensors no configuration group compiles (a test's).

#include "skyfuse/core/indirect_view.hpp"
#include "skyfuse/tracking/central_tracker.hpp"

namespace skyfuse {

template <typename Model, typename Sensor>
UpdateReport CentralTracker<Model, Sensor>::update_stacked(
    std::span<const Observation* const> stacked) {
  return update(IndirectView<Observation>(stacked));
}

}  // namespace skyfuse
