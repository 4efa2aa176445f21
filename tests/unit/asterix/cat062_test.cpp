// CAT062 ed. 1.19, item by item against bytes worked out from the standard's definitions, then
// whole records, then round trips within each item's LSB.
#include "skyfuse/asterix/cat062.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "asterix_samples.hpp"
#include "skyfuse/asterix/datagram.hpp"
#include "skyfuse/asterix/units.hpp"

namespace skyfuse::asterix {
namespace {

using testing::sample_track;

Bytes item(const SystemTrack& track, std::uint16_t number) {
  return testing::encoded_item(encode_cat062_record, uap_cat062(), track, number);
}

TEST(AsterixCat062, DataSourceServiceAndTrackNumber) {
  EXPECT_EQ(item(sample_track(), 10), (Bytes{0x19, 0x64}));  // SAC 25, SIC 100
  EXPECT_EQ(item(sample_track(), 15), Bytes{0x01});
  EXPECT_EQ(item(sample_track(), 40), (Bytes{0x10, 0x92}));  // 4242 = 0x1092
}

TEST(AsterixCat062, TimeOfTrackIn128thsOfASecond) {
  // 45296.5 s × 128 = 5 797 952 = 0x587840.
  EXPECT_EQ(item(sample_track(), 70), (Bytes{0x58, 0x78, 0x40}));
  auto t = sample_track();
  t.time_of_track_s = 86399.999;  // rounds to 86400 s: midnight, written as 0
  EXPECT_EQ(item(t, 70), (Bytes{0x00, 0x00, 0x00}));
  t.time_of_track_s = 86400.0;
  EXPECT_FALSE(encode_cat062_record(t));
  t.time_of_track_s = -0.001;
  EXPECT_FALSE(encode_cat062_record(t));
}

TEST(AsterixCat062, Wgs84PositionIn180Over2To25Degrees) {
  // -45° = -2^23 LSB = 0xFF800000; -90° = -2^24 LSB = 0xFF000000.
  EXPECT_EQ(item(sample_track(), 105), (Bytes{0xFF, 0x80, 0x00, 0x00, 0xFF, 0x00, 0x00, 0x00}));
  auto t = sample_track();
  t.latitude_deg = 90.0;    // 2^24 = 0x01000000
  t.longitude_deg = 180.0;  // the same meridian as -180°: -2^25 = 0xFE000000
  EXPECT_EQ(item(t, 105), (Bytes{0x01, 0x00, 0x00, 0x00, 0xFE, 0x00, 0x00, 0x00}));
  t.latitude_deg = 90.1;
  EXPECT_FALSE(encode_cat062_record(t));
}

TEST(AsterixCat062, CartesianPositionInHalfMetres) {
  // X -1000.5 m = -2001 LSB = 0x1000000 - 0x7D1 = 0xFFF82F; Y 2500.25 m = 5000.5 LSB, a tie,
  // rounds away from zero to 5001 = 0x001389.
  EXPECT_EQ(item(sample_track(), 100), (Bytes{0xFF, 0xF8, 0x2F, 0x00, 0x13, 0x89}));
  auto t = sample_track();
  t.x_m = 4194304.0;  // 2^23 LSB: one past the 24-bit field's maximum
  const auto refused = encode_cat062_record(t);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error->item, "I062/100 X");
}

TEST(AsterixCat062, VelocityInQuarterMetresPerSecond) {
  // VX -120.3 m/s = -481.2 LSB → -481 = 0xFE1F; VY 64.125 m/s = 256.5 LSB → 257 = 0x0101.
  EXPECT_EQ(item(sample_track(), 185), (Bytes{0xFE, 0x1F, 0x01, 0x01}));
  auto t = sample_track();
  t.vy_mps = 8192.0;  // 32768 LSB: refused, not wrapped to -8192
  EXPECT_FALSE(encode_cat062_record(t));
}

TEST(AsterixCat062, TrackStatusTakesTheOctetsItsFlagsNeed) {
  // Confirmed multisensor track, nothing else: the primary octet alone.
  EXPECT_EQ(item(sample_track(), 80), Bytes{0x00});
  auto t = sample_track();
  t.status.mono_sensor = true;  // MON, bit 8
  t.status.tentative = true;    // CNF, bit 2
  t.status.coasting = true;     // CST, bit 8 of the third extension
  // 0x80 | 0x02 | FX; first and second extensions empty but for FX; third: CST.
  EXPECT_EQ(item(t, 80), (Bytes{0x83, 0x01, 0x01, 0x80}));
  t = sample_track();
  t.status.first_message = true;  // TSB, bit 6 of the first extension
  EXPECT_EQ(item(t, 80), (Bytes{0x01, 0x20}));
  t = sample_track();
  t.geometric_altitude_m = 3048.0;
  t.status.altitude_source = 3;  // triangulation
  // MRH (bit 6) = geometric more reliable, SRC (bits 5-3) = 3: 0x20 | 0x0C.
  EXPECT_EQ(item(t, 80), Bytes{0x2C});
}

TEST(AsterixCat062, OptionalIdentityItems) {
  auto t = sample_track();
  EXPECT_TRUE(item(t, 60).empty());
  EXPECT_TRUE(item(t, 380).empty());
  t.mode3a = 07123;  // octal digits 7 1 2 3 = 111 001 010 011 = 0xE53
  t.address = 0x4CA2B3;
  EXPECT_EQ(item(t, 60), (Bytes{0x0E, 0x53}));
  // I062/380: primary subfield 0x80 (ADR, subfield #1, alone), then the 24-bit address.
  EXPECT_EQ(item(t, 380), (Bytes{0x80, 0x4C, 0xA2, 0xB3}));
  t.mode3a = 010000;
  EXPECT_FALSE(encode_cat062_record(t));
  t.mode3a.reset();
  t.address = 0x1000000;
  EXPECT_FALSE(encode_cat062_record(t));
}

// I062/245: STI 0 (downlinked from the target) and 6 spare bits, then eight 6-bit characters,
// padded with spaces: K L M 1 0 2 3 space = 11 12 13 49 48 50 51 32.
TEST(AsterixCat062, TargetIdentificationInSixBitCharacters) {
  auto t = sample_track();
  EXPECT_TRUE(item(t, 245).empty());
  t.callsign = "KLM1023";
  EXPECT_EQ(item(t, 245), (Bytes{0x00, 0x2C, 0xC3, 0x71, 0xC3, 0x2C, 0xE0}));
  t.callsign = "ABC";  // 1 2 3, then five spaces (32)
  EXPECT_EQ(item(t, 245), (Bytes{0x00, 0x04, 0x20, 0xE0, 0x82, 0x08, 0x20}));
  // Outside ICAO's set (no lower case, no punctuation), longer than 8, or nothing to send.
  for (const char* refused : {"klm1023", "KLM-1023", "ABCDEFGHI", "", "   "}) {
    t.callsign = refused;
    EXPECT_FALSE(encode_cat062_record(t)) << "'" << refused << "'";
  }
}

// A received I062/245 whose STI says "invalid", or whose characters are eight spaces, gives no
// callsign; one holding a code outside the set refuses the record.
TEST(AsterixCat062, AnInvalidOrBlankIdentificationIsNoCallsignAndABadCodeIsRefused) {
  auto t = sample_track();
  t.callsign = "KLM1023";
  const SystemTrack tracks[] = {t};
  const auto block = encode_cat062(tracks);
  ASSERT_TRUE(block);
  const Bytes i245 = item(t, 245);
  const auto at = std::search(block.bytes.begin(), block.bytes.end(), i245.begin(), i245.end());
  ASSERT_NE(at, block.bytes.end());
  const auto offset = static_cast<std::size_t>(at - block.bytes.begin());
  EXPECT_EQ(decode_datagram(block.bytes).tracks.at(0).callsign, "KLM1023");

  Bytes invalid = block.bytes;
  invalid[offset] = 0xC0;  // STI 3
  const auto decoded_invalid = decode_datagram(invalid);
  ASSERT_EQ(decoded_invalid.tracks.size(), 1u);
  EXPECT_FALSE(decoded_invalid.tracks[0].callsign.has_value());

  Bytes blank = block.bytes;
  const Bytes spaces{0x82, 0x08, 0x20, 0x82, 0x08, 0x20};  // eight times 32
  std::copy(spaces.begin(), spaces.end(), blank.begin() + static_cast<std::ptrdiff_t>(offset + 1));
  const auto decoded_blank = decode_datagram(blank);
  ASSERT_EQ(decoded_blank.tracks.size(), 1u);
  EXPECT_FALSE(decoded_blank.tracks[0].callsign.has_value());

  Bytes bad = block.bytes;
  bad[offset + 1] = 0x00;  // the first character's code 0: outside the set
  const auto decoded_bad = decode_datagram(bad);
  EXPECT_TRUE(decoded_bad.tracks.empty());
  EXPECT_EQ(decoded_bad.refusals.total(), 1u);
}

TEST(AsterixCat062, GeometricAltitudeIn6Point25Feet) {
  auto t = sample_track();
  t.geometric_altitude_m = 3048.0;  // 10 000 ft = 1600 LSB = 0x0640
  EXPECT_EQ(item(t, 130), (Bytes{0x06, 0x40}));
  t.geometric_altitude_m = -1000 * kMetresPerFoot;  // -160 LSB = 0xFF60
  EXPECT_EQ(item(t, 130), (Bytes{0xFF, 0x60}));
  t.geometric_altitude_m = -1600 * kMetresPerFoot;  // below the standard's -1500 ft
  EXPECT_FALSE(encode_cat062_record(t));
}

TEST(AsterixCat062, AccuracyFromTheCovarianceClampsAsTheStandardSays) {
  auto t = sample_track();
  t.accuracy = TrackAccuracy{12.3, 7.0, -20.25, 1.1, 0.6, std::nullopt};
  // Primary: APC (#1, 0x80), COV (#2, 0x40), ATV (#6, 0x04) = 0xC4. APC: 12.3 m = 24.6 → 25
  // = 0x0019, 7 m = 14 = 0x000E. COV: -sqrt(20.25) = -4.5 m = -9 LSB = 0xFFF7. ATV: 1.1 m/s =
  // 4.4 → 4, 0.6 m/s = 2.4 → 2.
  EXPECT_EQ(item(t, 500), (Bytes{0xC4, 0x00, 0x19, 0x00, 0x0E, 0xFF, 0xF7, 0x04, 0x02}));
  t.accuracy->sigma_altitude_m = 30.0;  // 98.4 ft = 15.7 LSB → 16: AGA (#4, 0x10) before ATV
  EXPECT_EQ(item(t, 500), (Bytes{0xD4, 0x00, 0x19, 0x00, 0x0E, 0xFF, 0xF7, 0x10, 0x04, 0x02}));
  // "Maximum value means maximum value or above": 100 km → 0xFFFF, 1e12 m² → 32767, 100 m/s →
  // 255.
  t.accuracy = TrackAccuracy{1e5, 0.0, 1e12, 100.0, 0.0, std::nullopt};
  EXPECT_EQ(item(t, 500), (Bytes{0xC4, 0xFF, 0xFF, 0x00, 0x00, 0x7F, 0xFF, 0xFF, 0x00}));
  t.accuracy->sigma_x_m = -1.0;
  EXPECT_FALSE(encode_cat062_record(t));
}

TEST(AsterixCat062, AWholeRecordAndBlock) {
  // FSPEC of 010 015 070 105 100 185 (FRNs 1, 3-7) and 040 080 (FRNs 12, 13): 0xBF (FX), 0x0C.
  const Bytes expected_record{0xBF, 0x0C,                                      // FSPEC
                              0x19, 0x64,                                      // 010
                              0x01,                                            // 015
                              0x58, 0x78, 0x40,                                // 070
                              0xFF, 0x80, 0x00, 0x00, 0xFF, 0x00, 0x00, 0x00,  // 105
                              0xFF, 0xF8, 0x2F, 0x00, 0x13, 0x89,              // 100
                              0xFE, 0x1F, 0x01, 0x01,                          // 185
                              0x10, 0x92,                                      // 040
                              0x00};                                           // 080
  EXPECT_EQ(encode_cat062_record(sample_track()).bytes, expected_record);
  const SystemTrack tracks[] = {sample_track()};
  Bytes expected_block{62, 0x00, static_cast<std::uint8_t>(3 + expected_record.size())};
  expected_block.insert(expected_block.end(), expected_record.begin(), expected_record.end());
  EXPECT_EQ(encode_cat062(tracks).bytes, expected_block);
}

TEST(AsterixCat062, EveryOptionalItemInOneFspec) {
  auto t = sample_track();
  t.mode3a = 07123;
  t.callsign = "KLM1023";
  t.address = 0x4CA2B3;
  t.geometric_altitude_m = 3048.0;
  t.accuracy = TrackAccuracy{};
  const auto record = encode_cat062_record(t);
  ASSERT_TRUE(record);
  // + 060 (FRN 9), 245 (10), 380 (11), 130 (18), 500 (27): 0xBF, 0x7D, 0x11, 0x04.
  EXPECT_EQ(Bytes(record.bytes.begin(), record.bytes.begin() + 4), (Bytes{0xBF, 0x7D, 0x11, 0x04}));
}

// Decoding what was encoded gives every value back within half its item's LSB.
void expect_round_trip(const SystemTrack& in) {
  const SystemTrack tracks[] = {in};
  const auto block = encode_cat062(tracks);
  ASSERT_TRUE(block) << block.error->item << ": " << block.error->reason;
  const auto decoded = decode_datagram(block.bytes);
  ASSERT_EQ(decoded.tracks.size(), 1u);
  EXPECT_EQ(decoded.refusals.total(), 0u);
  const auto& out = decoded.tracks[0];
  EXPECT_EQ(out.source, in.source);
  EXPECT_EQ(out.service_id, in.service_id);
  EXPECT_EQ(out.track_number, in.track_number);
  EXPECT_NEAR(out.time_of_track_s, in.time_of_track_s, 1.0 / 256 + 1e-9);
  EXPECT_EQ(out.status, in.status);
  EXPECT_NEAR(out.x_m, in.x_m, 0.25 + 1e-9);
  EXPECT_NEAR(out.y_m, in.y_m, 0.25 + 1e-9);
  const double half_wgs84 = 180.0 / std::ldexp(1.0, 26);
  EXPECT_NEAR(out.latitude_deg, in.latitude_deg, half_wgs84 + 1e-12);
  EXPECT_NEAR(out.longitude_deg, in.longitude_deg, half_wgs84 + 1e-12);
  EXPECT_NEAR(out.vx_mps, in.vx_mps, 0.125 + 1e-9);
  EXPECT_NEAR(out.vy_mps, in.vy_mps, 0.125 + 1e-9);
  EXPECT_EQ(out.mode3a, in.mode3a);
  EXPECT_EQ(out.callsign, in.callsign);
  EXPECT_EQ(out.address, in.address);
  ASSERT_EQ(out.geometric_altitude_m.has_value(), in.geometric_altitude_m.has_value());
  if (in.geometric_altitude_m) {
    EXPECT_NEAR(*out.geometric_altitude_m, *in.geometric_altitude_m, 3.125 * kMetresPerFoot + 1e-9);
  }
  ASSERT_EQ(out.accuracy.has_value(), in.accuracy.has_value());
  if (in.accuracy) {
    EXPECT_NEAR(out.accuracy->sigma_x_m, in.accuracy->sigma_x_m, 0.25 + 1e-9);
    EXPECT_NEAR(out.accuracy->sigma_y_m, in.accuracy->sigma_y_m, 0.25 + 1e-9);
    const double root_in = std::copysign(std::sqrt(std::fabs(in.accuracy->covariance_xy_m2)),
                                         in.accuracy->covariance_xy_m2);
    const double root_out = std::copysign(std::sqrt(std::fabs(out.accuracy->covariance_xy_m2)),
                                          out.accuracy->covariance_xy_m2);
    EXPECT_NEAR(root_out, root_in, 0.25 + 1e-9);
    EXPECT_NEAR(out.accuracy->sigma_vx_mps, in.accuracy->sigma_vx_mps, 0.125 + 1e-9);
    EXPECT_NEAR(out.accuracy->sigma_vy_mps, in.accuracy->sigma_vy_mps, 0.125 + 1e-9);
  }
}

TEST(AsterixCat062, RoundTripsWithinEachItemsResolution) {
  expect_round_trip(sample_track());
  std::mt19937_64 rng(54);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 500; ++i) {
    SystemTrack t;
    t.source = {static_cast<std::uint8_t>(rng()), static_cast<std::uint8_t>(rng())};
    t.service_id = static_cast<std::uint8_t>(rng());
    t.track_number = static_cast<std::uint16_t>(rng());
    t.time_of_track_s = u(rng) * 86399.0;
    t.x_m = (u(rng) - 0.5) * 8e6;
    t.y_m = (u(rng) - 0.5) * 8e6;
    t.latitude_deg = (u(rng) - 0.5) * 179.9;
    t.longitude_deg = (u(rng) - 0.5) * 359.9;
    t.vx_mps = (u(rng) - 0.5) * 16000.0;
    t.vy_mps = (u(rng) - 0.5) * 16000.0;
    t.status.mono_sensor = (rng() & 1) != 0;
    t.status.tentative = (rng() & 1) != 0;
    t.status.coasting = (rng() & 1) != 0;
    t.status.last_message = (rng() & 1) != 0;
    if ((rng() & 1) != 0) t.mode3a = static_cast<std::uint16_t>(rng() & 07777);
    if ((rng() & 1) != 0) t.address = static_cast<std::uint32_t>(rng() & 0xFFFFFF);
    if ((rng() & 1) != 0) t.callsign = testing::random_callsign(rng);
    if ((rng() & 1) != 0) t.geometric_altitude_m = (u(rng) * 40000.0 - 400.0);
    if ((rng() & 1) != 0) {
      t.accuracy = TrackAccuracy{u(rng) * 1000, u(rng) * 1000, (u(rng) - 0.5) * 1e5,
                                 u(rng) * 60,   u(rng) * 60,   std::nullopt};
    }
    expect_round_trip(t);
  }
}

}  // namespace
}  // namespace skyfuse::asterix
