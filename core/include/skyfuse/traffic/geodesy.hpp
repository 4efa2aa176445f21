#pragma once
/// \file
/// WGS-84 geodesy: geodetic (latitude, longitude, height above the ellipsoid) to and from
/// Earth-centred Earth-fixed coordinates, and the local east-north-up frame of a GeoAnchor, so
/// that positions recorded as latitude and longitude can be placed in a scenario's frame.
/// Angles are in degrees, as recordings and scenario files give them; lengths in metres.

#include "skyfuse/core/types.hpp"
#include "skyfuse/scenario/scenario.hpp"

namespace skyfuse {

/// The WGS-84 ellipsoid: semi-major axis (m) and flattening, the defining constants of GPS and
/// of ADS-B positions.
inline constexpr double kWgs84SemiMajorAxisM = 6378137.0;
inline constexpr double kWgs84Flattening = 1.0 / 298.257223563;

/// Earth-centred Earth-fixed position (m) of a point `height_m` above the ellipsoid.
Vector3 geodetic_to_ecef(double latitude_deg, double longitude_deg, double height_m);

/// (latitude deg, longitude deg, height m) of an ECEF position: Bowring's iteration on the
/// parametric latitude, which converges to machine precision in a few steps for every height
/// an aircraft or a ground station has, poles included. Longitude is in (-180, 180].
Vector3 ecef_to_geodetic(const Vector3& ecef);

/// The rotation from ECEF to the east-north-up axes at a latitude and longitude: its rows are
/// the east, north and up unit vectors. Directions (velocities) are turned with it alone;
/// positions also need the origin subtracted (to_local_enu).
Matrix3 ecef_to_enu_rotation(double latitude_deg, double longitude_deg);

/// (east, north, up) in metres of a geodetic point about `anchor`, whose altitude_m is taken
/// as its height above the ellipsoid. Up is along the anchor's ellipsoid normal, so a point on
/// the anchor's height surface lies below the plane z = 0 by about d^2 / (2 R) at distance d.
Vector3 to_local_enu(const GeoAnchor& anchor, double latitude_deg, double longitude_deg,
                     double height_m);

/// (latitude deg, longitude deg, height m) of a point given in `anchor`'s east-north-up frame.
Vector3 from_local_enu(const GeoAnchor& anchor, const Vector3& enu);

/// East-north-up velocity (m/s) from a ground speed, a heading in degrees clockwise from true
/// north (OpenSky's `heading`: 90 flies east) and a vertical rate (positive climbing), in the
/// local frame of the aircraft itself.
Vector3 enu_velocity(double speed_mps, double heading_deg, double vertical_rate_mps);

}  // namespace skyfuse
