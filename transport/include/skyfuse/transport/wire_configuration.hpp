#pragma once
/// \file
/// Which motion model the station and center processes run. No Fast DDS here: the plan loading
/// that refuses other models includes this.

#include "skyfuse/core/types.hpp"
#include "skyfuse/models/constant_acceleration.hpp"
#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/tracking/peer_contribution.hpp"

namespace skyfuse::transport {

/// The motion model the station and center processes are compiled for: the 9-state
/// constant-acceleration model, with any registered sensors, mixed or not. Other models run
/// in-process (require_wire_configuration says so before anything starts).
using WireModel = ConstantAcceleration3D;
using WireContribution = PeerContribution<WireModel::kDim>;
using WireEstimate = GaussianState<WireModel::kDim>;

/// Refuses, with std::invalid_argument naming it, a scenario whose motion model the station
/// and center processes are not compiled for. Any registered sensor runs, mixed or not.
void require_wire_configuration(const Scenario& scenario);

}  // namespace skyfuse::transport
