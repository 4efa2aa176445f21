// CAT021 ed. 2.6, item by item against bytes worked out from the standard's definitions, then
// a whole record, then round trips within each item's LSB.
#include "skyfuse/asterix/cat021.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "asterix_samples.hpp"
#include "skyfuse/asterix/datagram.hpp"
#include "skyfuse/asterix/units.hpp"

namespace skyfuse::asterix {
namespace {

using testing::sample_report;

Bytes item(const AdsbReport& report, std::uint16_t number) {
  return testing::encoded_item(encode_cat021_record, uap_cat021(), report, number);
}

TEST(AsterixCat021, DataSourceTimesAndAddress) {
  EXPECT_EQ(item(sample_report(), 10), (Bytes{0x19, 0x0B}));        // SAC 25, SIC 11
  EXPECT_EQ(item(sample_report(), 71), (Bytes{0x58, 0x78, 0x40}));  // 45296.5 s × 128
  EXPECT_EQ(item(sample_report(), 73), (Bytes{0x58, 0x78, 0x60}));  // 45296.75 s × 128
  EXPECT_EQ(item(sample_report(), 80), (Bytes{0xA1, 0xB2, 0xC3}));
}

TEST(AsterixCat021, TargetReportDescriptor) {
  // ATP 0 (ICAO address), ARC 0 (25 ft), RC 0, RAB 0, FX; extension: all 0 (GBS, SIM, TST,
  // SAA = capable, CL = valid).
  EXPECT_EQ(item(sample_report(), 40), (Bytes{0x01, 0x00}));
  auto r = sample_report();
  r.address_type = 3;        // anonymous: 3 << 5 = 0x60
  r.altitude_reporting = 1;  // 100 ft: 1 << 3 = 0x08
  r.ground = true;           // GBS, bit 7 of the extension
  r.test_target = true;      // TST, bit 5
  EXPECT_EQ(item(r, 40), (Bytes{0x69, 0x50}));
  r.address_type = 4;  // reserved
  EXPECT_FALSE(encode_cat021_record(r));
}

TEST(AsterixCat021, PositionInEitherResolution) {
  // I021/131: LSB 180/2^30 deg: -45° = -2^28 = 0xF0000000, -90° = -2^29 = 0xE0000000.
  EXPECT_EQ(item(sample_report(), 131), (Bytes{0xF0, 0x00, 0x00, 0x00, 0xE0, 0x00, 0x00, 0x00}));
  EXPECT_TRUE(item(sample_report(), 130).empty());
  auto r = sample_report();
  r.position_items = PositionItems::low_resolution;
  // I021/130: LSB 180/2^23 deg in 24 bits: -45° = -2^21 = 0xE00000, -90° = -2^22 = 0xC00000.
  EXPECT_EQ(item(r, 130), (Bytes{0xE0, 0x00, 0x00, 0xC0, 0x00, 0x00}));
  EXPECT_TRUE(item(r, 131).empty());
  r.position_items = PositionItems::both;
  EXPECT_FALSE(item(r, 130).empty());
  EXPECT_FALSE(item(r, 131).empty());
}

TEST(AsterixCat021, GeometricHeightIn6Point25Feet) {
  auto r = sample_report();
  r.geometric_height_m = 3048.0;  // 10 000 ft = 1600 = 0x0640
  EXPECT_EQ(item(r, 140), (Bytes{0x06, 0x40}));
  r.geometric_height_m = 150000 * kMetresPerFoot;  // the standard's range ends below 150 000 ft
  EXPECT_FALSE(encode_cat021_record(r));
}

TEST(AsterixCat021, QualityIndicatorsWithTwoExtensions) {
  auto r = sample_report();
  r.quality = AdsbQuality{2, 8, 1, 3, 9, 0, 2, 1};
  // Primary: NACv 2 << 5 = 0x40, NIC 8 << 1 = 0x10, FX: 0x51. First extension: NICbaro 0x80,
  // SIL 3 << 5 = 0x60, NACp 9 << 1 = 0x12, FX: 0xF3. Second: SILS 0, SDA 2 << 3 = 0x10, GVA
  // 1 << 1 = 0x02: 0x12.
  EXPECT_EQ(item(r, 90), (Bytes{0x51, 0xF3, 0x12}));
  r.quality.nacp = 16;
  EXPECT_FALSE(encode_cat021_record(r));
}

TEST(AsterixCat021, AirborneGroundVector) {
  auto r = sample_report();
  // 250 kt = 250/3600 NM/s = 1137.8 LSB of 2^-14 NM/s → 1138 = 0x0472; 45° = 8192 = 0x2000.
  r.ground_vector = GroundVector{250 * kMetresPerNauticalMile / 3600, 45.0};
  EXPECT_EQ(item(r, 160), (Bytes{0x04, 0x72, 0x20, 0x00}));
  r.ground_vector->ground_speed_mps = 2 * kMetresPerNauticalMile;  // 2 NM/s: past 15 bits
  EXPECT_FALSE(encode_cat021_record(r));
}

TEST(AsterixCat021, GeometricVerticalRate) {
  auto r = sample_report();
  // 1 000 ft/min climbing = 160 LSB of 6.25 ft/min = 0x00A0; 500 ft/min descending = -80 in
  // 15 bits of two's complement = 0x7FB0, RE (bit 16) clear.
  r.vertical_rate_mps = 1000.0 * kMetresPerFoot / 60.0;
  EXPECT_EQ(item(r, 157), (Bytes{0x00, 0xA0}));
  r.vertical_rate_mps = -500.0 * kMetresPerFoot / 60.0;
  EXPECT_EQ(item(r, 157), (Bytes{0x7F, 0xB0}));
  r.vertical_rate_mps = 102'400.0 * kMetresPerFoot / 60.0;  // 16 384 LSB: past 15 bits
  EXPECT_FALSE(encode_cat021_record(r));
  // Read back with RE set, the rate is a bound only: the report has none.
  r.vertical_rate_mps = 0.0;
  auto record = encode_cat021_record(r);
  ASSERT_TRUE(record);
  const auto at = record.bytes.size() - 2;  // 157 is the last item written here
  ASSERT_EQ(record.bytes[at], 0x00);
  record.bytes[at] = 0x80;
  const std::size_t length = record.bytes.size() + 3;
  Bytes block{kCat021, static_cast<std::uint8_t>(length >> 8U),
              static_cast<std::uint8_t>(length & 0xFFU)};
  block.insert(block.end(), record.bytes.begin(), record.bytes.end());
  const auto decoded = decode_datagram(block);
  ASSERT_EQ(decoded.reports.size(), 1u);
  EXPECT_FALSE(decoded.reports[0].vertical_rate_mps.has_value());
}

TEST(AsterixCat021, AWholeRecordsFspec) {
  auto r = sample_report();
  r.geometric_height_m = 3048.0;
  r.ground_vector = GroundVector{100.0, 10.0};
  const auto record = encode_cat021_record(r);
  ASSERT_TRUE(record);
  // FRNs 1 2 5 7 (010 040 071 131) + FX: 0xCB; 11 12 (080 073) + FX: 0x19; 16 17 (140 090) +
  // FX: 0x61; 26 (160): 0x08.
  EXPECT_EQ(Bytes(record.bytes.begin(), record.bytes.begin() + 4), (Bytes{0xCB, 0x19, 0x61, 0x08}));
  // FSPEC 4 + 010 2 + 040 2 + 071 3 + 131 8 + 080 3 + 073 3 + 140 2 + 090 3 + 160 4.
  EXPECT_EQ(record.bytes.size(), 34u);
  // + 170 (FRN 29): the fourth octet 0x09 (160, FX), a fifth 0x80.
  r.callsign = "KLM1023";
  const auto identified = encode_cat021_record(r);
  ASSERT_TRUE(identified);
  EXPECT_EQ(Bytes(identified.bytes.begin(), identified.bytes.begin() + 5),
            (Bytes{0xCB, 0x19, 0x61, 0x09, 0x80}));
  EXPECT_EQ(identified.bytes.size(), 34u + 1u + 6u);
}

// I021/170: eight 6-bit characters, padded with spaces: K L M 1 0 2 3 space = 11 12 13 49 48
// 50 51 32. Eight spaces read back as no callsign; a code outside the set refuses the report.
TEST(AsterixCat021, TargetIdentificationInSixBitCharacters) {
  auto r = sample_report();
  EXPECT_TRUE(item(r, 170).empty());
  r.callsign = "KLM1023";
  EXPECT_EQ(item(r, 170), (Bytes{0x2C, 0xC3, 0x71, 0xC3, 0x2C, 0xE0}));
  r.callsign = "klm1023";
  EXPECT_FALSE(encode_cat021_record(r));

  r.callsign = "KLM1023";
  const AdsbReport reports[] = {r};
  const auto block = encode_cat021(reports);
  ASSERT_TRUE(block);
  EXPECT_EQ(decode_datagram(block.bytes).reports.at(0).callsign, "KLM1023");
  const auto offset = block.bytes.size() - 6;  // 170 is the last item written here
  Bytes blank = block.bytes;
  const Bytes spaces{0x82, 0x08, 0x20, 0x82, 0x08, 0x20};
  std::copy(spaces.begin(), spaces.end(), blank.begin() + static_cast<std::ptrdiff_t>(offset));
  EXPECT_FALSE(decode_datagram(blank).reports.at(0).callsign.has_value());
  Bytes bad = block.bytes;
  bad[offset + 5] = 0x3F;  // the last character's code 63: outside the set
  const auto decoded_bad = decode_datagram(bad);
  EXPECT_TRUE(decoded_bad.reports.empty());
  EXPECT_EQ(decoded_bad.refusals.total(), 1u);
}

void expect_round_trip(const AdsbReport& in) {
  const AdsbReport reports[] = {in};
  const auto block = encode_cat021(reports);
  ASSERT_TRUE(block) << block.error->item << ": " << block.error->reason;
  const auto decoded = decode_datagram(block.bytes);
  ASSERT_EQ(decoded.reports.size(), 1u);
  EXPECT_EQ(decoded.refusals.total(), 0u);
  const auto& out = decoded.reports[0];
  EXPECT_EQ(out.source, in.source);
  EXPECT_EQ(out.address_type, in.address_type);
  EXPECT_EQ(out.altitude_reporting, in.altitude_reporting);
  EXPECT_EQ(out.ground, in.ground);
  EXPECT_EQ(out.simulated, in.simulated);
  EXPECT_EQ(out.test_target, in.test_target);
  EXPECT_NEAR(out.time_of_applicability_s, in.time_of_applicability_s, 1.0 / 256 + 1e-9);
  EXPECT_NEAR(out.time_of_reception_s, in.time_of_reception_s, 1.0 / 256 + 1e-9);
  EXPECT_EQ(out.address, in.address);
  EXPECT_EQ(out.position_items, in.position_items);
  const int scale = in.position_items == PositionItems::low_resolution ? 24 : 31;
  const double half = 180.0 / std::ldexp(1.0, scale);
  EXPECT_NEAR(out.latitude_deg, in.latitude_deg, half + 1e-12);
  EXPECT_NEAR(out.longitude_deg, in.longitude_deg, half + 1e-12);
  ASSERT_EQ(out.geometric_height_m.has_value(), in.geometric_height_m.has_value());
  if (in.geometric_height_m) {
    EXPECT_NEAR(*out.geometric_height_m, *in.geometric_height_m, 3.125 * kMetresPerFoot + 1e-9);
  }
  EXPECT_EQ(out.quality, in.quality);
  EXPECT_EQ(out.callsign, in.callsign);
  ASSERT_EQ(out.vertical_rate_mps.has_value(), in.vertical_rate_mps.has_value());
  if (in.vertical_rate_mps) {
    EXPECT_NEAR(*out.vertical_rate_mps, *in.vertical_rate_mps,
                3.125 * kMetresPerFoot / 60.0 + 1e-12);
  }
  ASSERT_EQ(out.ground_vector.has_value(), in.ground_vector.has_value());
  if (in.ground_vector) {
    EXPECT_NEAR(out.ground_vector->ground_speed_mps, in.ground_vector->ground_speed_mps,
                std::ldexp(1.0, -15) * kMetresPerNauticalMile + 1e-9);
    const double turn = std::remainder(
        out.ground_vector->track_angle_deg - in.ground_vector->track_angle_deg, 360.0);
    EXPECT_NEAR(turn, 0.0, 180.0 / 65536 + 1e-9);
  }
}

TEST(AsterixCat021, RoundTripsWithinEachItemsResolution) {
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 500; ++i) {
    AdsbReport r;
    r.source = {static_cast<std::uint8_t>(rng()), static_cast<std::uint8_t>(rng())};
    r.address_type = static_cast<std::uint8_t>(rng() % 4);
    r.altitude_reporting = static_cast<std::uint8_t>(rng() % 4);
    r.ground = (rng() & 1) != 0;
    r.simulated = (rng() & 1) != 0;
    r.test_target = (rng() & 1) != 0;
    r.time_of_applicability_s = u(rng) * 86399.0;
    r.time_of_reception_s = u(rng) * 86399.0;
    r.address = static_cast<std::uint32_t>(rng() & 0xFFFFFF);
    r.latitude_deg = (u(rng) - 0.5) * 179.9;
    r.longitude_deg = (u(rng) - 0.5) * 359.9;
    r.position_items = static_cast<PositionItems>(rng() % 3);
    if ((rng() & 1) != 0) r.geometric_height_m = u(rng) * 40000.0 - 400.0;
    r.quality =
        AdsbQuality{static_cast<std::uint8_t>(rng() % 8),  static_cast<std::uint8_t>(rng() % 16),
                    static_cast<std::uint8_t>(rng() % 2),  static_cast<std::uint8_t>(rng() % 4),
                    static_cast<std::uint8_t>(rng() % 16), static_cast<std::uint8_t>(rng() % 2),
                    static_cast<std::uint8_t>(rng() % 4),  static_cast<std::uint8_t>(rng() % 4)};
    if ((rng() & 1) != 0) r.ground_vector = GroundVector{u(rng) * 3000.0, (u(rng) - 0.5) * 720.0};
    if ((rng() & 1) != 0) r.vertical_rate_mps = (u(rng) - 0.5) * 1000.0;  // ±500 m/s
    if ((rng() & 1) != 0) r.callsign = testing::random_callsign(rng);
    expect_round_trip(r);
  }
}

}  // namespace
}  // namespace skyfuse::asterix
