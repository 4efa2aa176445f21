#pragma once
/// \file
/// Which motion model and sensor today's wire types carry. No Fast DDS here: the option parsing
/// that refuses other configurations includes this.

#include "skyfuse/fusion/station_observation.hpp"
#include "skyfuse/models/constant_acceleration.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/tracking/peer_contribution.hpp"

namespace skyfuse::transport {

/// The motion model the station and center processes are compiled for: the 9-state
/// constant-acceleration model, with any registered sensors, mixed or not. Other models run
/// in-process (require_wire_configuration says so before anything starts). WireSensor is
/// paper 000's station, what the rogue test tool impersonates.
using WireModel = ConstantAcceleration3D;
using WireSensor = RangeAzimuthElevation<WireModel::kDim>;
using WireObservation = StationObservation<WireSensor>;
using WireContribution = PeerContribution<WireModel::kDim>;
using WireEstimate = GaussianState<WireModel::kDim>;

/// Refuses, with std::invalid_argument naming it, a scenario whose motion model the station
/// and center processes are not compiled for. Any registered sensor runs, mixed or not.
void require_wire_configuration(const Scenario& scenario, int stations);

}  // namespace skyfuse::transport
