#pragma once
// CAT021, ADS-B target reports, EUROCONTROL ASTERIX Part 12, edition 2.6 (the edition
// Wireshark 4.0 decodes by default). Written per report, in UAP order:
//
//   I021/010 data source          SAC, SIC
//   I021/040 target report descriptor  ATP, ARC, RC, RAB; first extension (DCR, GBS, SIM,
//                                 TST, SAA, CL) always, so that GBS and CL are explicit
//   I021/071 time of applicability for position  24 bits unsigned, LSB 1/128 s
//   I021/130 position             optional form; 2 × 24 bits two's complement, LSB 180/2^23 deg
//   I021/131 high-resolution position  2 × 32 bits two's complement, LSB 180/2^30 deg
//   I021/080 target address       24 bits
//   I021/073 time of message reception for position  24 bits unsigned, LSB 1/128 s
//   I021/140 geometric height     optional; 16 bits two's complement, LSB 6.25 ft
//   I021/090 quality indicators   NUCr/NACv, NUCp/NIC; first extension NICbaro, SIL, NACp;
//                                 second extension SIL-supplement, SDA, GVA
//   I021/157 geometric vertical rate  optional; RE = 0, 15 bits two's complement, LSB 6.25
//                                 ft/min (±102 400 ft/min); read with RE set as absent
//   I021/160 airborne ground vector  optional; RE = 0, GS 15 bits unsigned, LSB 2^-14 NM/s
//                                 (< 2 NM/s), TA 16 bits, LSB 360/2^16 deg (an angle: mod 360)
//   I021/170 target identification  optional; 8 characters of ICAO's 6-bit set (A-Z, 0-9,
//                                 space), the callsign the aircraft broadcasts
//
// Which of 130/131 is written is the caller's choice (PositionItems); the decoder takes 131
// when both are present. Every other item of the edition's UAP is skipped.

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "skyfuse/asterix/bytes.hpp"
#include "skyfuse/asterix/data_source.hpp"
#include "skyfuse/asterix/record_walker.hpp"

namespace skyfuse::asterix {

inline constexpr std::uint8_t kCat021 = 21;

enum class PositionItems : std::uint8_t { high_resolution, low_resolution, both };

/// I021/090: the quality indicators as the aircraft's MOPS version defines them (raw codes).
struct AdsbQuality {
  std::uint8_t nucr_or_nacv = 0;    ///< 3 bits
  std::uint8_t nucp_or_nic = 0;     ///< 4 bits
  std::uint8_t nic_baro = 0;        ///< 1 bit
  std::uint8_t sil = 0;             ///< 2 bits
  std::uint8_t nacp = 0;            ///< 4 bits
  std::uint8_t sil_supplement = 0;  ///< 1 bit: 0 per flight hour, 1 per sample
  std::uint8_t sda = 0;             ///< 2 bits
  std::uint8_t gva = 0;             ///< 2 bits
  bool operator==(const AdsbQuality&) const = default;
};

struct GroundVector {
  double ground_speed_mps = 0;  ///< [0, 2 NM/s)
  double track_angle_deg = 0;   ///< clockwise from true north; any value, taken mod 360
};

struct AdsbReport {
  DataSource source;  ///< I021/010
  /// I021/040 ATP: 0 24-bit ICAO address, 1 duplicate, 2 surface vehicle, 3 anonymous.
  std::uint8_t address_type = 0;
  /// I021/040 ARC: 0 25 ft, 1 100 ft, 2 unknown, 3 invalid.
  std::uint8_t altitude_reporting = 0;
  bool ground = false;                 ///< I021/040 GBS
  bool simulated = false;              ///< I021/040 SIM
  bool test_target = false;            ///< I021/040 TST
  double time_of_applicability_s = 0;  ///< I021/071, [0, 86400)
  double time_of_reception_s = 0;      ///< I021/073, [0, 86400)
  std::uint32_t address = 0;           ///< I021/080, 24 bits
  double latitude_deg = 0;             ///< I021/131 (or 130), [-90, 90]
  double longitude_deg = 0;            ///< [-180, 180)
  PositionItems position_items = PositionItems::high_resolution;
  std::optional<double> geometric_height_m;   ///< I021/140, [-1500, 150000) ft
  AdsbQuality quality;                        ///< I021/090
  std::optional<double> vertical_rate_mps;    ///< I021/157, geometric, up positive
  std::optional<GroundVector> ground_vector;  ///< I021/160
  /// I021/170, without its trailing spaces: 1 to 8 of A-Z, 0-9 and space.
  std::optional<std::string> callsign;
};

Encoded encode_cat021_record(const AdsbReport& report);
Encoded encode_cat021(std::span<const AdsbReport> reports);

/// The report a walked CAT021 record carries, or why it is refused: value_out_of_range (a
/// reserved ATP, a ground speed with RE set, ...), or missing_item when 010, 040, 071, 073,
/// 080, 090 or both 130 and 131 are absent.
using Cat021Decoded = RecordOutcome<AdsbReport>;
Cat021Decoded decode_cat021_record(const WalkedRecord& record);

}  // namespace skyfuse::asterix
