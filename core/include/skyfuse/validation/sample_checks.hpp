#pragma once
/// \file
/// Content checks a receiver applies to a sample before it may be fused: the checks that need
/// no knowledge of the run (the run id, step window and station ids are checked by the
/// receiver and its StepCollector). Each returns the first problem found, or nothing.

#include <optional>

#include "skyfuse/fusion/information_increment.hpp"
#include "skyfuse/fusion/stacked_ekf.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/tracking/peer_tracker.hpp"
#include "skyfuse/validation/drop_kind.hpp"

namespace skyfuse {

/// What a range/azimuth/elevation sensor can report: range in (0, kMaxRangeM], azimuth in
/// [-pi, pi], elevation in [-pi/2, pi/2].
inline constexpr double kMaxRangeM = 1.0e6;

/// Largest plausible entry of an increment's dQ: the information of a range known to 3e-8 m.
/// Finite but larger values pass every other check and then overflow the fused sum, which
/// would stop the receiving station (found by fuzzing).
inline constexpr double kMaxInformation = 1.0e15;
/// Largest plausible entry of a prior's mean and covariance (SI units): far beyond any track.
inline constexpr double kMaxStateMagnitude = 1.0e12;

/// dQ and dy finite; their entries within kMaxInformation (dy: times kMaxRangeM); dQ positive
/// semi-definite (smallest eigenvalue >= -1e-9 times the largest magnitude: rounding in
/// H^T R^-1 H is allowed, a negative direction is not).
std::optional<DropKind> check_increment(const InformationIncrement<9>& increment);

/// Mean and covariance finite and within kMaxStateMagnitude; covariance positive definite (a
/// prior or a track a peer may adopt).
std::optional<DropKind> check_estimate(const GaussianState<9>& estimate);

/// The increment as check_increment(), then the prior it travels with as check_estimate().
std::optional<DropKind> check_contribution(const PeerContribution& contribution);

/// z finite and within what the sensor can report (see kMaxRangeM): kOutOfRange or
/// kNonFinite otherwise. The part of check_observation that needs z alone.
std::optional<DropKind> check_reported_values(const Vector3& z);

/// z, R and the station position finite; R positive definite; z within the sensor's range and
/// the station within kMaxRangeM of the origin.
std::optional<DropKind> check_observation(
    const StationObservation<RangeAzimuthElevation<9>>& observation);

}  // namespace skyfuse
