#pragma once
/// \file
/// Magnitudes beyond which a value on the wire cannot come from a real aircraft, station or
/// filter. Receivers refuse such samples (DropKind::kOutOfRange); each sensor's own limits are
/// in its header, stated in terms of these.

namespace skyfuse {

/// Largest plausible distance (m) between the origin, a station and an aircraft.
inline constexpr double kMaxRangeM = 1.0e6;
/// Largest plausible speed (m/s) of a tracked aircraft: about Mach 30.
inline constexpr double kMaxSpeedMps = 1.0e4;

/// Largest plausible entry of an increment's dQ: the information of a range known to 3e-8 m.
/// Finite but larger values pass every other check and then overflow the fused sum, which
/// would stop the receiving station (found by fuzzing).
inline constexpr double kMaxInformation = 1.0e15;
/// Largest plausible entry of a prior's mean and covariance (SI units): far beyond any track.
inline constexpr double kMaxStateMagnitude = 1.0e12;

}  // namespace skyfuse
