#pragma once
/// \file
/// The truth of a run with many aircraft: each aircraft's kinematics over the steps it is
/// present. Where it comes from — a scenario's list of targets, the traffic generator, a
/// recorded file — is the business of whoever makes it; the sensors and the metrics read only
/// this.

#include <cstddef>
#include <string>
#include <vector>

#include "skyfuse/core/types.hpp"
#include "skyfuse/picture/address.hpp"
#include "skyfuse/scenario/truth.hpp"

namespace skyfuse {

/// One aircraft, present from step `first_step` to `first_step + states.size() - 1`.
struct TargetTruth {
  /// A name for people and recordings: "T3" for the third target of a scenario, the ICAO 24-bit
  /// address of a recorded aircraft.
  std::string label;
  int first_step = 0;
  /// [p; v; a] (m, m/s, m/s^2, the scenario's east-north-up frame) at each step it is present.
  std::vector<Vector<kKinematicsDim>> states;
  /// The address it reports to cooperative sensors (picture/address.hpp); kNoAddress for
  /// an aircraft that carries no transponder nor broadcast, which only primary radars see.
  Address address = kNoAddress;

  bool present_at(int step) const {
    return step >= first_step && step < first_step + static_cast<int>(states.size());
  }
  /// Its kinematics at `step`; present_at(step) must hold.
  const Vector<kKinematicsDim>& at(int step) const {
    return states[static_cast<std::size_t>(step - first_step)];
  }
};

}  // namespace skyfuse
