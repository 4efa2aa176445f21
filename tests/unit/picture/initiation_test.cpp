#include "skyfuse/picture/initiation.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "skyfuse/models/position_velocity.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"

namespace skyfuse {
namespace {

PositionFix fix_at(int station, std::uint32_t detection, const Vector3& p, double std_m) {
  return {station, detection, p, std_m * std_m * Covariance<3>::Identity(),
          Covariance<3>::Identity() / (std_m * std_m)};
}

TEST(Initiation, DetectionsOfTwoStationsThatAgreeStartOneTrack) {
  const std::vector<PositionFix> fixes = {fix_at(1, 0, {100, 0, 50}, 5.0),
                                          fix_at(1, 1, {5000, 0, 50}, 5.0),
                                          fix_at(2, 4, {103, 2, 50}, 5.0)};
  const auto started = initiate_tracks(fixes, 9, InitiationConfig{});
  ASSERT_EQ(started.size(), 1U);
  EXPECT_EQ(started[0].id, make_track_id(9, 1, 0));
  EXPECT_EQ(started[0].stations, (std::vector<int>{1, 2}));
  // Equal covariances: the fused position is the mean, with half the variance.
  EXPECT_NEAR((started[0].position - Vector3(101.5, 1.0, 50.0)).norm(), 0.0, 1e-9);
  EXPECT_NEAR(started[0].covariance(0, 0), 12.5, 1e-9);
}

TEST(Initiation, OneStationsDetectionAloneStartsNothingByDefault) {
  const std::vector<PositionFix> fixes = {fix_at(1, 0, {100, 0, 50}, 5.0),
                                          fix_at(2, 0, {900, 0, 50}, 5.0)};
  EXPECT_TRUE(initiate_tracks(fixes, 1, InitiationConfig{}).empty());
  InitiationConfig single;
  single.min_stations = 1;
  EXPECT_EQ(initiate_tracks(fixes, 1, single).size(), 2U);
}

TEST(Initiation, AGroupTakesOneDetectionPerStation) {
  // Two detections of station 2 near station 1's: only the first joins.
  const std::vector<PositionFix> fixes = {
      fix_at(1, 0, {0, 0, 0}, 5.0), fix_at(2, 0, {1, 0, 0}, 5.0), fix_at(2, 1, {2, 0, 0}, 5.0)};
  const auto started = initiate_tracks(fixes, 0, InitiationConfig{});
  ASSERT_EQ(started.size(), 1U);
  EXPECT_EQ(started[0].stations, (std::vector<int>{1, 2}));
}

PositionFix addressed(PositionFix fix, Address address) {
  fix.address = address;
  return fix;
}

TEST(Initiation, AnAddressedDetectionStartsATrackByItself) {
  const std::vector<PositionFix> fixes = {addressed(fix_at(2, 3, {100, 0, 50}, 10.0), 0xABC),
                                          fix_at(3, 0, {900, 0, 50}, 5.0)};
  const auto started = initiate_tracks(fixes, 4, InitiationConfig{});
  ASSERT_EQ(started.size(), 1U) << "the unaddressed one alone starts nothing";
  EXPECT_EQ(started[0].id, make_track_id(4, 2, 3));
  EXPECT_EQ(started[0].address, 0xABCU);
  EXPECT_FALSE(started[0].velocity.has_value()) << "the fix reported none";
}

TEST(Initiation, AnUnaddressedDetectionAndAnAddressedOneThatAgreeAreOneTrackWithTheAddress) {
  const std::vector<PositionFix> fixes = {fix_at(1, 0, {100, 0, 50}, 5.0),
                                          addressed(fix_at(2, 0, {104, 0, 50}, 10.0), 0xABC)};
  const auto started = initiate_tracks(fixes, 0, InitiationConfig{});
  ASSERT_EQ(started.size(), 1U);
  EXPECT_EQ(started[0].stations, (std::vector<int>{1, 2}));
  EXPECT_EQ(started[0].address, 0xABCU);
}

TEST(Initiation, DetectionsOfTwoAddressesNeverGroupAndAnAddressStartsOneTrack) {
  const std::vector<PositionFix> fixes = {addressed(fix_at(1, 0, {100, 0, 50}, 5.0), 0xA),
                                          addressed(fix_at(2, 0, {101, 0, 50}, 5.0), 0xB),
                                          addressed(fix_at(3, 0, {9000, 0, 50}, 5.0), 0xA)};
  const auto started = initiate_tracks(fixes, 0, InitiationConfig{});
  ASSERT_EQ(started.size(), 2U) << "0xA's second report, 9 km away, starts no second track";
  EXPECT_EQ(started[0].address, 0xAU);
  EXPECT_EQ(started[0].stations, std::vector<int>{1});
  EXPECT_EQ(started[1].address, 0xBU);
  EXPECT_EQ(started[1].stations, std::vector<int>{2});
}

TEST(PositionFixes, APositionVelocityReportGivesItsVelocityWithItsNoise) {
  const PositionVelocity<6> receiver;
  Vector<6> z;
  z << 1.0, 2.0, 3.0, 40.0, -5.0, 0.5;
  Covariance<6> noise = Covariance<6>::Identity() * 100.0;
  noise.bottomRightCorner<3, 3>() = Covariance<3>::Identity() * 0.25;
  const auto fix = fix_position(2, 0, receiver, z, noise);
  ASSERT_TRUE(fix.has_value());
  ASSERT_TRUE(fix->velocity.has_value());
  EXPECT_EQ(*fix->velocity, Vector3(40.0, -5.0, 0.5));
  EXPECT_EQ(fix->velocity_covariance, Covariance<3>::Identity() * 0.25);

  std::vector<PositionFix> fixes = {*fix};
  fixes[0].address = 0x77;
  const auto started = initiate_tracks(fixes, 0, InitiationConfig{});
  ASSERT_EQ(started.size(), 1U);
  ASSERT_TRUE(started[0].velocity.has_value());
  EXPECT_EQ(*started[0].velocity, Vector3(40.0, -5.0, 0.5));
}

TEST(Initiation, RefusesFixesOutOfOrder) {
  const std::vector<PositionFix> fixes = {fix_at(2, 0, {0, 0, 0}, 5.0),
                                          fix_at(1, 0, {0, 0, 0}, 5.0)};
  EXPECT_THROW(initiate_tracks(fixes, 0, InitiationConfig{}), std::invalid_argument);
}

TEST(PositionFixes, ARadarsDetectionIsInvertedToItsPositionWithCrossRangeSpread) {
  const RangeAzimuthElevation<6> radar(Vector3(10, 20, 0));
  const Vector3 target(1010, 20, 0);  // 1 km east, level
  Covariance<3> noise = Covariance<3>::Zero();
  noise.diagonal() << 4.0, 1e-6, 1e-6;  // 2 m range, 1 mrad angles
  const auto fix = fix_position(3, 7, radar, radar.measure_position(target), noise);
  ASSERT_TRUE(fix);
  EXPECT_NEAR((fix->position - target).norm(), 0.0, 1e-9);
  EXPECT_NEAR(fix->covariance(0, 0), 4.0, 1e-9);  // along the beam: the range variance
  EXPECT_NEAR(fix->covariance(1, 1), 1.0, 1e-9);  // across: (1000 m x 1 mrad)^2
  EXPECT_NEAR(fix->covariance(2, 2), 1.0, 1e-9);
}

TEST(PositionFixes, APositionVelocityDetectionFixesItsPosition) {
  const PositionVelocity<9> sensor;
  Vector<6> z;
  z << 1, 2, 3, 4, 5, 6;
  const Covariance<6> noise = 9.0 * Covariance<6>::Identity();
  const auto fix = fix_position(1, 0, sensor, z, noise);
  ASSERT_TRUE(fix);
  EXPECT_EQ(fix->position, Vector3(1, 2, 3));
  EXPECT_NEAR(fix->covariance(0, 0), 9.0, 1e-12);
}

}  // namespace
}  // namespace skyfuse
