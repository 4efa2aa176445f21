#include "skyfuse/traffic/geodesy.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>

namespace skyfuse {
namespace {

/// 1e-6 m on positions of thousands of kilometres is a few ulps above rounding.
constexpr double kMetres = 1e-6;
constexpr double kDegrees = 1e-9;

void expect_near(const Vector3& actual, const Vector3& expected, double tolerance) {
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(actual(i), expected(i), tolerance) << "component " << i;
  }
}

// Expected figures: a and b = a (1 - f) of WGS-84 on the axes, and values computed once with
// 40-digit arithmetic from the ellipsoid's definition (N = a / sqrt(1 - e^2 sin^2 lat)).
TEST(Geodesy, PointsOnTheAxesLieAtTheSemiAxes) {
  expect_near(geodetic_to_ecef(0.0, 0.0, 0.0), Vector3(6378137.0, 0.0, 0.0), kMetres);
  expect_near(geodetic_to_ecef(0.0, 90.0, 0.0), Vector3(0.0, 6378137.0, 0.0), kMetres);
  expect_near(geodetic_to_ecef(0.0, 180.0, 1000.0), Vector3(-6379137.0, 0.0, 0.0), kMetres);
  expect_near(geodetic_to_ecef(90.0, 0.0, 0.0), Vector3(0.0, 0.0, 6356752.314245179), kMetres);
  expect_near(geodetic_to_ecef(-90.0, 0.0, -1000.0), Vector3(0.0, 0.0, -6355752.314245179),
              kMetres);
}

TEST(Geodesy, PointsOffTheAxesMatchPublishedFigures) {
  expect_near(geodetic_to_ecef(45.0, 45.0, 0.0),
              Vector3(3194419.145061, 3194419.145061, 4487348.408866), kMetres);
  // The default anchor, near Munich, at its 480 m.
  expect_near(geodetic_to_ecef(48.24, 11.67, 480.0),
              Vector3(4168188.537329, 860914.539991, 4735049.372193), kMetres);
  // Sydney, 10 km up: southern and eastern hemisphere, height away from zero.
  expect_near(geodetic_to_ecef(-33.8568, 151.2153, 10000.0),
              Vector3(-4654246.841578, 2557075.616244, -3538838.318850), kMetres);
}

TEST(Geodesy, EcefToGeodeticInvertsTheFixedPoints) {
  expect_near(ecef_to_geodetic(Vector3(6378137.0, 0.0, 0.0)), Vector3(0.0, 0.0, 0.0), kMetres);
  const Vector3 pole = ecef_to_geodetic(Vector3(0.0, 0.0, 6356752.314245179));
  EXPECT_NEAR(pole.x(), 90.0, kDegrees);
  EXPECT_NEAR(pole.z(), 0.0, kMetres);
  const Vector3 munich = ecef_to_geodetic(Vector3(4168188.537329, 860914.539991, 4735049.372193));
  EXPECT_NEAR(munich.x(), 48.24, kDegrees);
  EXPECT_NEAR(munich.y(), 11.67, kDegrees);
  EXPECT_NEAR(munich.z(), 480.0, 1e-5);  // the figure's own rounding at 1e-6 m per axis
}

TEST(Geodesy, GeodeticRoundTripHoldsFromBelowSeaLevelToTheEdgeOfSpace) {
  for (double lat = -90.0; lat <= 90.0; lat += 7.5) {
    for (double lon = -180.0; lon < 180.0; lon += 22.5) {
      for (const double height : {-1000.0, 0.0, 480.0, 11000.0, 100000.0}) {
        const Vector3 back = ecef_to_geodetic(geodetic_to_ecef(lat, lon, height));
        EXPECT_NEAR(back.x(), lat, kDegrees) << lat << ", " << lon << ", " << height;
        EXPECT_NEAR(back.z(), height, kMetres) << lat << ", " << lon << ", " << height;
        // Longitude means nothing at a pole; -180 and 180 are the same meridian.
        if (std::abs(lat) < 90.0) {
          EXPECT_NEAR(std::remainder(back.y() - lon, 360.0), 0.0, kDegrees)
              << lat << ", " << lon << ", " << height;
        }
      }
    }
  }
}

TEST(Geodesy, TheAnchorIsTheOriginOfItsFrame) {
  const GeoAnchor anchor;
  expect_near(to_local_enu(anchor, anchor.latitude_deg, anchor.longitude_deg, anchor.altitude_m),
              Vector3::Zero(), kMetres);
}

TEST(Geodesy, APointOneKilometreNorthDropsBelowTheAnchorPlaneByTheEarthsCurvature) {
  const GeoAnchor anchor{48.24, 11.67, 480.0};
  // 0.0089925335 deg of latitude is 1000 m of meridian arc here (radius of curvature
  // M + h = 6371483.6 m); the drop d^2 / (2 (M + h)) is 0.0785 m.
  const Vector3 enu = to_local_enu(anchor, 48.2489925335, 11.67, 480.0);
  expect_near(enu, Vector3(0.0, 1000.000783, -0.078475), kMetres);
}

TEST(Geodesy, APointEastAndAboveTheAnchorHasTheExpectedFrameCoordinates) {
  const GeoAnchor anchor{48.24, 11.67, 480.0};
  // 0.03 deg of longitude at 48.24 deg; the meridians converge, so the point lies slightly
  // north as well, and 1000 m up minus the curvature drop.
  const Vector3 enu = to_local_enu(anchor, 48.24, 11.7, 1480.0);
  expect_near(enu, Vector3(2228.873189, 0.435270, 999.611370), kMetres);
}

TEST(Geodesy, FromLocalEnuInvertsToLocalEnu) {
  const GeoAnchor anchor{-33.8568, 151.2153, 25.0};
  for (const Vector3& enu : {Vector3(0.0, 0.0, 0.0), Vector3(1500.0, -2500.0, 300.0),
                             Vector3(-150000.0, 80000.0, 11000.0)}) {
    const Vector3 geodetic = from_local_enu(anchor, enu);
    expect_near(to_local_enu(anchor, geodetic.x(), geodetic.y(), geodetic.z()), enu, kMetres);
  }
  expect_near(from_local_enu(anchor, Vector3::Zero()),
              Vector3(anchor.latitude_deg, anchor.longitude_deg, anchor.altitude_m), kDegrees);
}

TEST(Geodesy, HeadingIsClockwiseFromNorth) {
  expect_near(enu_velocity(100.0, 0.0, 0.0), Vector3(0.0, 100.0, 0.0), 1e-12);
  expect_near(enu_velocity(100.0, 90.0, 2.5), Vector3(100.0, 0.0, 2.5), 1e-12);
  expect_near(enu_velocity(100.0, 180.0, -3.0), Vector3(0.0, -100.0, -3.0), 1e-12);
  expect_near(enu_velocity(100.0, 270.0, 0.0), Vector3(-100.0, 0.0, 0.0), 1e-12);
  expect_near(enu_velocity(200.0, 45.0, 0.0), Vector3(141.421356237, 141.421356237, 0.0), 1e-9);
}

TEST(Geodesy, TheEnuRotationIsOrthonormalWithUpAlongTheNormal) {
  const Matrix3 rotation = ecef_to_enu_rotation(48.24, 11.67);
  EXPECT_TRUE((rotation * rotation.transpose()).isApprox(Matrix3::Identity(), 1e-14));
  EXPECT_NEAR(rotation.determinant(), 1.0, 1e-14);
  // Up at the equator and prime meridian is +x; north there is +z.
  expect_near(ecef_to_enu_rotation(0.0, 0.0).row(2).transpose(), Vector3::UnitX(), 1e-15);
  expect_near(ecef_to_enu_rotation(0.0, 0.0).row(1).transpose(), Vector3::UnitZ(), 1e-15);
}

}  // namespace
}  // namespace skyfuse
