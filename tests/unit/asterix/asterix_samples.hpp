#pragma once
// Values the ASTERIX tests share: one track, plot and report whose bytes the item tests work
// out by hand, and the item bytes of an encoded record.

#include <gtest/gtest.h>

#include <string>
#include <string_view>
#include <vector>

#include "skyfuse/asterix/cat021.hpp"
#include "skyfuse/asterix/cat048.hpp"
#include "skyfuse/asterix/cat062.hpp"
#include "skyfuse/asterix/record_walker.hpp"

namespace skyfuse::asterix::testing {

/// The octets of `item` in `record` (an encoded record of the category of `uap`); empty when
/// the record does not carry the item.
inline Bytes item_of(const Bytes& record, std::span<const UapEntry> uap, std::uint16_t item) {
  const auto walked = walk_record(record, uap);
  const auto* found = find_item(walked, item);
  return found == nullptr ? Bytes{} : Bytes(found->bytes.begin(), found->bytes.end());
}

/// The octets of `item` in the record `encode` makes of `value`, which must encode.
template <typename T>
Bytes encoded_item(Encoded (*encode)(const T&), std::span<const UapEntry> uap, const T& value,
                   std::uint16_t item) {
  const auto record = encode(value);
  EXPECT_TRUE(record) << (record.error ? record.error->item + ": " + record.error->reason : "");
  return item_of(record.bytes, uap, item);
}

/// A callsign of 1 to 8 characters of ICAO's 6-bit set (A-Z, 0-9, space) that ends in one
/// that is not a space, as a decoder gives it back (it drops the padding).
template <typename Rng>
std::string random_callsign(Rng& rng) {
  static constexpr std::string_view kSet = "ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789 ";
  const std::size_t length = 1 + rng() % 8;
  std::string callsign;
  for (std::size_t i = 0; i < length; ++i) {
    callsign.push_back(kSet[rng() % (i + 1 == length ? kSet.size() - 1 : kSet.size())]);
  }
  return callsign;
}

/// 12:34:56.5 UTC: 45296.5 s = 5 797 952 / 128 s = 0x587840 LSB.
inline constexpr double kTimeOfDay = 45296.5;

/// Values chosen to be exact in their items' LSBs where the tests compare bytes, south and west
/// of the origin so that every signed field is negative.
inline SystemTrack sample_track() {
  SystemTrack t;
  t.source = {25, 100};
  t.service_id = 1;
  t.track_number = 4242;
  t.time_of_track_s = kTimeOfDay;
  t.x_m = -1000.5;
  t.y_m = 2500.25;  // 5000.5 LSB: a tie, rounds away from zero to 5001
  t.latitude_deg = -45.0;
  t.longitude_deg = -90.0;
  t.vx_mps = -120.3;
  t.vy_mps = 64.125;
  return t;
}

inline RadarPlot sample_plot() {
  RadarPlot p;
  p.source = {25, 10};
  p.time_of_day_s = kTimeOfDay;
  p.detection = DetectionType::mode_s_roll_call;
  p.range_m = 100 * 1852.0;  // 100 NM
  p.azimuth_deg = 90.0;
  return p;
}

inline AdsbReport sample_report() {
  AdsbReport r;
  r.source = {25, 11};
  r.time_of_applicability_s = kTimeOfDay;
  r.time_of_reception_s = kTimeOfDay + 0.25;
  r.address = 0xA1B2C3;
  r.latitude_deg = -45.0;
  r.longitude_deg = -90.0;
  return r;
}

}  // namespace skyfuse::asterix::testing
