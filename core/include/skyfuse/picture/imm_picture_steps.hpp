#pragma once
/// \file
/// The IMM picture's two steps that depend on a station's sensor: a peer's contribution of one
/// detection and the center's stacked update of a track's detections. They are declared here and
/// compiled once per mode set and picture sensor in core (src/picture/imm_picture_steps*),
/// not in every file of the picture that runs the IMM: with both sensors in one file they made
/// the IMM's picture files the build's largest (docs/testing.md).

#include <span>

#include "skyfuse/core/status.hpp"
#include "skyfuse/fusion/station_observation.hpp"
#include "skyfuse/tracking/network_imm.hpp"
#include "skyfuse/tracking/round_rule.hpp"

namespace skyfuse {

template <typename Set, typename Sensor>
struct ImmPictureSteps {
  using Peer = typename NetworkImm<Set>::Peer;
  using Central = typename NetworkImm<Set>::Central;
  /// A peer's contribution of `o` against its track's modes, ungated (the pair was gated).
  static OwnContribution contribute(const Peer& state, const StationObservation<Sensor>& o,
                                    typename Peer::Contribution& out);
  /// Every mode's stacked update of `observations`, weighed by its likelihood.
  static NumericalStatus update(Central& state,
                                std::span<const StationObservation<Sensor>> observations);
};

}  // namespace skyfuse
