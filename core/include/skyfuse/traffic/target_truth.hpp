#pragma once
/// \file
/// The truth of a run with many aircraft: each aircraft's kinematics over the steps it is
/// present. Where it comes from — a scenario's list of targets, the traffic generator, a
/// recorded file — is the business of whoever makes it; the sensors and the metrics read only
/// this.

#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

#include "skyfuse/core/types.hpp"
#include "skyfuse/picture/address.hpp"
#include "skyfuse/picture/identification.hpp"
#include "skyfuse/scenario/truth.hpp"

namespace skyfuse {

/// A position report a recorded aircraft broadcast (its own ADS-B position and velocity), as a
/// ground receiver hears it at a step: the newest report sent since the step before, carried
/// forward to the step's time along the velocity it reported.
struct HeardBroadcast {
  int step = 0;
  /// [p; v] (m, m/s, the scenario's frame) at the step's time.
  Vector<6> position_velocity = Vector<6>::Zero();
  /// How long before the step's time the report was sent (s), in [0, time_step_s).
  double age_s = 0.0;
};

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
  /// The callsign it reports with its address (picture/identification.hpp): a recorded
  /// aircraft's from its file, a simulated one's made of its address; none without an address.
  Identification identification = kNoIdentification;
  /// A recorded aircraft's own reports, one at each step it sent one, in step order
  /// (traffic/recorded_traffic.hpp); empty for a simulated aircraft, whose reports a cooperative
  /// sensor draws from its kinematics instead.
  std::vector<HeardBroadcast> broadcasts{};

  bool present_at(int step) const {
    return step >= first_step && step < first_step + static_cast<int>(states.size());
  }
  /// Its kinematics at `step`; present_at(step) must hold.
  const Vector<kKinematicsDim>& at(int step) const {
    return states[static_cast<std::size_t>(step - first_step)];
  }
  /// Its broadcast heard at `step`, or null where it sent none since the step before.
  const HeardBroadcast* broadcast_at(int step) const {
    const auto heard =
        std::lower_bound(broadcasts.begin(), broadcasts.end(), step,
                         [](const HeardBroadcast& b, int at) { return b.step < at; });
    return heard != broadcasts.end() && heard->step == step ? &*heard : nullptr;
  }
};

}  // namespace skyfuse
