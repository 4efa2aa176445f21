#include "skyfuse/traffic/geodesy.hpp"

#include <cmath>
#include <numbers>

namespace skyfuse {
namespace {

constexpr double kA = kWgs84SemiMajorAxisM;
constexpr double kB = kA * (1.0 - kWgs84Flattening);
/// First and second eccentricity squared.
constexpr double kE2 = kWgs84Flattening * (2.0 - kWgs84Flattening);
constexpr double kEp2 = kE2 / (1.0 - kE2);

constexpr double kRadPerDeg = std::numbers::pi / 180.0;
constexpr double kDegPerRad = 180.0 / std::numbers::pi;

/// Bowring's iteration gains about three digits a step from its starting guess; five steps
/// reach rounding for heights within thousands of kilometres, and it stops earlier once the
/// latitude stops moving.
constexpr int kMaxLatitudeIterations = 8;

}  // namespace

Vector3 geodetic_to_ecef(double latitude_deg, double longitude_deg, double height_m) {
  const double lat = latitude_deg * kRadPerDeg;
  const double lon = longitude_deg * kRadPerDeg;
  const double sin_lat = std::sin(lat);
  const double cos_lat = std::cos(lat);
  // Prime-vertical radius of curvature: distance along the normal to the polar axis.
  const double n = kA / std::sqrt(1.0 - kE2 * sin_lat * sin_lat);
  return Vector3((n + height_m) * cos_lat * std::cos(lon), (n + height_m) * cos_lat * std::sin(lon),
                 (n * (1.0 - kE2) + height_m) * sin_lat);
}

Vector3 ecef_to_geodetic(const Vector3& ecef) {
  const double p = std::hypot(ecef.x(), ecef.y());
  const double z = ecef.z();
  const double lon = std::atan2(ecef.y(), ecef.x());

  // Parametric (reduced) latitude beta and geodetic latitude lat, refined in turn.
  double beta = std::atan2(z, (1.0 - kWgs84Flattening) * p);
  double lat = 0.0;
  for (int i = 0; i < kMaxLatitudeIterations; ++i) {
    const double sin_beta = std::sin(beta);
    const double cos_beta = std::cos(beta);
    const double next = std::atan2(z + kEp2 * kB * sin_beta * sin_beta * sin_beta,
                                   p - kE2 * kA * cos_beta * cos_beta * cos_beta);
    const bool settled = i > 0 && std::abs(next - lat) < 1e-15;
    lat = next;
    if (settled) break;
    beta = std::atan2((1.0 - kWgs84Flattening) * std::sin(lat), std::cos(lat));
  }

  // Height along the normal, well conditioned at the poles too (unlike p / cos(lat) - N).
  const double sin_lat = std::sin(lat);
  const double cos_lat = std::cos(lat);
  const double height = p * cos_lat + z * sin_lat - kA * std::sqrt(1.0 - kE2 * sin_lat * sin_lat);
  return Vector3(lat * kDegPerRad, lon * kDegPerRad, height);
}

Matrix3 ecef_to_enu_rotation(double latitude_deg, double longitude_deg) {
  const double lat = latitude_deg * kRadPerDeg;
  const double lon = longitude_deg * kRadPerDeg;
  const double sin_lat = std::sin(lat);
  const double cos_lat = std::cos(lat);
  const double sin_lon = std::sin(lon);
  const double cos_lon = std::cos(lon);
  Matrix3 rotation;
  rotation << -sin_lon, cos_lon, 0.0,                   // east
      -sin_lat * cos_lon, -sin_lat * sin_lon, cos_lat,  // north
      cos_lat * cos_lon, cos_lat * sin_lon, sin_lat;    // up
  return rotation;
}

Vector3 to_local_enu(const GeoAnchor& anchor, double latitude_deg, double longitude_deg,
                     double height_m) {
  const Vector3 offset =
      geodetic_to_ecef(latitude_deg, longitude_deg, height_m) -
      geodetic_to_ecef(anchor.latitude_deg, anchor.longitude_deg, anchor.altitude_m);
  return ecef_to_enu_rotation(anchor.latitude_deg, anchor.longitude_deg) * offset;
}

Vector3 from_local_enu(const GeoAnchor& anchor, const Vector3& enu) {
  const Vector3 origin =
      geodetic_to_ecef(anchor.latitude_deg, anchor.longitude_deg, anchor.altitude_m);
  const Matrix3 rotation = ecef_to_enu_rotation(anchor.latitude_deg, anchor.longitude_deg);
  return ecef_to_geodetic(origin + rotation.transpose() * enu);
}

Vector3 enu_velocity(double speed_mps, double heading_deg, double vertical_rate_mps) {
  const double heading = heading_deg * kRadPerDeg;
  return Vector3(speed_mps * std::sin(heading), speed_mps * std::cos(heading), vertical_rate_mps);
}

}  // namespace skyfuse
