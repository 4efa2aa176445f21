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

/// The configuration today's wire types carry: the 9-state constant-acceleration model with
/// range/azimuth/elevation stations (paper 000). The processes run it; other configurations
/// run in-process (require_wire_configuration says so before anything starts).
using WireModel = ConstantAcceleration3D;
using WireSensor = RangeAzimuthElevation<WireModel::kDim>;
using WireObservation = StationObservation<WireSensor>;
using WireContribution = PeerContribution<WireModel::kDim>;
using WireEstimate = GaussianState<WireModel::kDim>;

/// Refuses, with std::invalid_argument naming the parts, a scenario whose first `stations`
/// stations or motion model the wire cannot carry yet.
void require_wire_configuration(const Scenario& scenario, int stations);

}  // namespace skyfuse::transport
