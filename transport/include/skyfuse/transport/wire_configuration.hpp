#pragma once
/// \file
/// Which motion model the station and center processes run. No Fast DDS here: the plan loading
/// that refuses other models includes this.

#include "skyfuse/core/types.hpp"
#include "skyfuse/models/constant_acceleration.hpp"
#include "skyfuse/models/tdoa/tdoa_relative_motion.hpp"
#include "skyfuse/options/node_options.hpp"
#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/tracking/peer_contribution.hpp"

namespace skyfuse::transport {

/// The motion model the station and center processes are compiled for: the 9-state
/// constant-acceleration model, with any registered sensors, mixed or not; and, for filter kind
/// ncrkf only, paper 002's relative model (TdoaRelativeMotion), of the same dimension, which the
/// wire types carry alike. Other models run in-process (require_wire_configuration says so
/// before anything starts).
using WireModel = ConstantAcceleration3D;
static_assert(TdoaRelativeMotion::kDim == WireModel::kDim);
using WireContribution = PeerContribution<WireModel::kDim>;
using WireEstimate = GaussianState<WireModel::kDim>;

/// Refuses, with std::invalid_argument naming it, a scenario whose motion model the station
/// and center processes are not compiled for, or node options its filter does not take: a NIS
/// gate for one with no innovation to gate (ncrkf), a re-fusion lag for the IMM. Any registered
/// sensor runs, mixed or not.
void require_wire_configuration(const Scenario& scenario, const options::NodeOptions& node);

}  // namespace skyfuse::transport
