// CAT048 ed. 1.31, item by item against bytes worked out from the standard's definitions, then
// a whole record, then round trips within each item's LSB.
#include "skyfuse/asterix/cat048.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "asterix_samples.hpp"
#include "skyfuse/asterix/datagram.hpp"
#include "skyfuse/asterix/units.hpp"

namespace skyfuse::asterix {
namespace {

using testing::sample_plot;

Bytes item(const RadarPlot& plot, std::uint16_t number) {
  return testing::encoded_item(encode_cat048_record, uap_cat048(), plot, number);
}

TEST(AsterixCat048, DataSourceAndTimeOfDay) {
  EXPECT_EQ(item(sample_plot(), 10), (Bytes{0x19, 0x0A}));         // SAC 25, SIC 10
  EXPECT_EQ(item(sample_plot(), 140), (Bytes{0x58, 0x78, 0x40}));  // 45296.5 s × 128
}

TEST(AsterixCat048, TargetReportDescriptor) {
  // TYP 5 (Mode S roll-call) in bits 8-6: 0xA0; no FX.
  EXPECT_EQ(item(sample_plot(), 20), Bytes{0xA0});
  auto p = sample_plot();
  p.detection = DetectionType::ssr_psr;  // TYP 3: 0x60
  p.simulated = true;                    // SIM, bit 5: 0x10
  EXPECT_EQ(item(p, 20), Bytes{0x70});
  p.test_target = true;  // FX, then TST in bit 8 of the first extension
  EXPECT_EQ(item(p, 20), (Bytes{0x71, 0x80}));
}

TEST(AsterixCat048, PolarPositionIn256thsOfANauticalMileAnd2To16thsOfATurn) {
  // RHO 100 NM = 25600 = 0x6400; THETA 90° = 16384 = 0x4000.
  EXPECT_EQ(item(sample_plot(), 40), (Bytes{0x64, 0x00, 0x40, 0x00}));
  auto p = sample_plot();
  p.azimuth_deg = -90.0;  // an angle: 270° = 49152 = 0xC000
  EXPECT_EQ(item(p, 40), (Bytes{0x64, 0x00, 0xC0, 0x00}));
  p.azimuth_deg = 359.999;  // 65535.8 LSB rounds to a whole turn: 0
  EXPECT_EQ(item(p, 40), (Bytes{0x64, 0x00, 0x00, 0x00}));
  p.range_m = 256 * kMetresPerNauticalMile;  // 65536 LSB: beyond the 16-bit field
  EXPECT_FALSE(encode_cat048_record(p));
}

TEST(AsterixCat048, ModeAFlightLevelAddressTrackNumber) {
  auto p = sample_plot();
  p.mode3a = 01234;        // 001 010 011 100 = 0x29C
  p.flight_level = 350.0;  // 1400 quarter-FL = 0x0578, V = G = 0
  p.address = 0x3C6586;
  p.track_number = 3000;  // 0x0BB8 under 4 spare bits
  EXPECT_EQ(item(p, 70), (Bytes{0x02, 0x9C}));
  EXPECT_EQ(item(p, 90), (Bytes{0x05, 0x78}));
  EXPECT_EQ(item(p, 220), (Bytes{0x3C, 0x65, 0x86}));
  EXPECT_EQ(item(p, 161), (Bytes{0x0B, 0xB8}));
  p.flight_level = -5.25;  // -21 in 14 bits two's complement: 0x3FEB
  EXPECT_EQ(item(p, 90), (Bytes{0x3F, 0xEB}));
  p.flight_level = 2048.0;  // 8192 quarter-FL: one past the 14-bit field
  EXPECT_FALSE(encode_cat048_record(p));
  p.flight_level.reset();
  p.track_number = 4096;
  EXPECT_FALSE(encode_cat048_record(p));
}

TEST(AsterixCat048, AWholeRecord) {
  auto p = sample_plot();
  p.mode3a = 01234;
  p.flight_level = 350.0;
  p.address = 0x3C6586;
  p.track_number = 3000;
  // FRNs 1-6 (010 140 020 040 070 090) and FX: 0xFD; FRN 8 (220) and 11 (161): 0x90.
  const Bytes expected{0xFD, 0x90, 0x19, 0x0A, 0x58, 0x78, 0x40, 0xA0, 0x64, 0x00, 0x40,
                       0x00, 0x02, 0x9C, 0x05, 0x78, 0x3C, 0x65, 0x86, 0x0B, 0xB8};
  EXPECT_EQ(encode_cat048_record(p).bytes, expected);
  // 010 140 020 040 only: FRNs 1-4, one octet.
  EXPECT_EQ(encode_cat048_record(sample_plot()).bytes[0], 0xF0);
}

// I048/240: eight 6-bit characters, padded with spaces (K L M 1 0 2 3 space = 11 12 13 49 48
// 50 51 32), FRN 9, between the address (8) and the track number (11).
TEST(AsterixCat048, AircraftIdentificationInSixBitCharacters) {
  auto p = sample_plot();
  EXPECT_TRUE(item(p, 240).empty());
  p.address = 0x3C6586;
  p.callsign = "KLM1023";
  EXPECT_EQ(item(p, 240), (Bytes{0x2C, 0xC3, 0x71, 0xC3, 0x2C, 0xE0}));
  p.track_number = 3000;
  const auto record = encode_cat048_record(p);
  ASSERT_TRUE(record);
  EXPECT_EQ(Bytes(record.bytes.begin(), record.bytes.begin() + 2), (Bytes{0xF1, 0xD0}));
  p.callsign = "KLM 1023X";  // nine characters
  EXPECT_FALSE(encode_cat048_record(p));
  p.callsign = "klm1023";
  EXPECT_FALSE(encode_cat048_record(p));
}

void expect_round_trip(const RadarPlot& in) {
  const RadarPlot plots[] = {in};
  const auto block = encode_cat048(plots);
  ASSERT_TRUE(block) << block.error->item << ": " << block.error->reason;
  const auto decoded = decode_datagram(block.bytes);
  ASSERT_EQ(decoded.plots.size(), 1u);
  EXPECT_EQ(decoded.refusals.total(), 0u);
  const auto& out = decoded.plots[0];
  EXPECT_EQ(out.source, in.source);
  EXPECT_NEAR(out.time_of_day_s, in.time_of_day_s, 1.0 / 256 + 1e-9);
  EXPECT_EQ(out.detection, in.detection);
  EXPECT_EQ(out.simulated, in.simulated);
  EXPECT_EQ(out.test_target, in.test_target);
  EXPECT_NEAR(out.range_m, in.range_m, kMetresPerNauticalMile / 512 + 1e-9);
  const double turn = std::remainder(out.azimuth_deg - in.azimuth_deg, 360.0);
  EXPECT_NEAR(turn, 0.0, 180.0 / 65536 + 1e-9);
  EXPECT_EQ(out.mode3a, in.mode3a);
  ASSERT_EQ(out.flight_level.has_value(), in.flight_level.has_value());
  if (in.flight_level) {
    EXPECT_NEAR(*out.flight_level, *in.flight_level, 0.125 + 1e-9);
  }
  EXPECT_EQ(out.address, in.address);
  EXPECT_EQ(out.callsign, in.callsign);
  EXPECT_EQ(out.track_number, in.track_number);
}

TEST(AsterixCat048, RoundTripsWithinEachItemsResolution) {
  std::mt19937_64 rng(48);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 500; ++i) {
    RadarPlot p;
    p.source = {static_cast<std::uint8_t>(rng()), static_cast<std::uint8_t>(rng())};
    p.time_of_day_s = u(rng) * 86399.0;
    p.detection = static_cast<DetectionType>(rng() % 8);
    p.simulated = (rng() & 1) != 0;
    p.test_target = (rng() & 1) != 0;
    p.range_m = u(rng) * 255.9 * kMetresPerNauticalMile;
    p.azimuth_deg = (u(rng) - 0.5) * 1000.0;
    if ((rng() & 1) != 0) p.mode3a = static_cast<std::uint16_t>(rng() & 07777);
    if ((rng() & 1) != 0) p.flight_level = (u(rng) - 0.5) * 4000.0;
    if ((rng() & 1) != 0) p.address = static_cast<std::uint32_t>(rng() & 0xFFFFFF);
    if ((rng() & 1) != 0) p.callsign = testing::random_callsign(rng);
    if ((rng() & 1) != 0) p.track_number = static_cast<std::uint16_t>(rng() & 0xFFF);
    expect_round_trip(p);
  }
}

}  // namespace
}  // namespace skyfuse::asterix
