#pragma once
// CAT048, monoradar target reports, EUROCONTROL ASTERIX Part 4, edition 1.31 (the edition
// Wireshark 4.0 decodes by default). Written per plot, in UAP order:
//
//   I048/010 data source        SAC, SIC
//   I048/140 time of day        24 bits unsigned, LSB 1/128 s, s since midnight UTC
//   I048/020 target report descriptor  TYP, SIM, RDP, SPI, RAB; first extension (TST) only
//                               when the test flag is set
//   I048/040 measured position  RHO 16 bits unsigned, LSB 1/256 NM (< 256 NM); THETA 16 bits,
//                               LSB 360/2^16 deg, clockwise from north (an angle: 360° is 0°)
//   I048/070 Mode 3/A code      optional; 12-bit octal code, V/G/L = 0
//   I048/090 flight level       optional; 14 bits two's complement, LSB 1/4 FL, V/G = 0
//   I048/220 aircraft address   optional; 24 bits
//   I048/240 aircraft identification  optional; 8 characters of ICAO's 6-bit set (A-Z, 0-9,
//                               space), the callsign a Mode S transponder downlinks
//   I048/161 track number       optional; 12 bits
//
// The decoder reads these items and skips every other item of the edition's UAP.

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "skyfuse/asterix/bytes.hpp"
#include "skyfuse/asterix/data_source.hpp"
#include "skyfuse/asterix/record_walker.hpp"

namespace skyfuse::asterix {

inline constexpr std::uint8_t kCat048 = 48;

/// I048/020 TYP: what detected the target.
enum class DetectionType : std::uint8_t {
  no_detection = 0,
  psr = 1,
  ssr = 2,
  ssr_psr = 3,
  mode_s_all_call = 4,
  mode_s_roll_call = 5,
  mode_s_all_call_psr = 6,
  mode_s_roll_call_psr = 7,
};

struct RadarPlot {
  DataSource source;                                          ///< I048/010
  double time_of_day_s = 0;                                   ///< I048/140, [0, 86400)
  DetectionType detection = DetectionType::mode_s_roll_call;  ///< I048/020 TYP
  bool simulated = false;                                     ///< I048/020 SIM
  bool test_target = false;                                   ///< I048/020 TST (first extension)
  double range_m = 0;                                         ///< I048/040 RHO, [0, 256 NM)
  double azimuth_deg = 0;  ///< I048/040 THETA, clockwise from north; any value, taken mod 360
  std::optional<std::uint16_t> mode3a;        ///< I048/070, the code's octal digits (07777 max)
  std::optional<double> flight_level;         ///< I048/090, [-2048, 2047.75] FL (hundreds of ft)
  std::optional<std::uint32_t> address;       ///< I048/220, 24 bits
  std::optional<std::string> callsign;        ///< I048/240, without its trailing spaces
  std::optional<std::uint16_t> track_number;  ///< I048/161, 12 bits
};

Encoded encode_cat048_record(const RadarPlot& plot);
Encoded encode_cat048(std::span<const RadarPlot> plots);

/// The plot a walked CAT048 record carries, or why it is refused: value_out_of_range, or
/// missing_item when 010, 140, 020 or 040 is absent.
using Cat048Decoded = RecordOutcome<RadarPlot>;
Cat048Decoded decode_cat048_record(const WalkedRecord& record);

}  // namespace skyfuse::asterix
