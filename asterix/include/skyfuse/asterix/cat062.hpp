#pragma once
// CAT062, SDPS system track messages, EUROCONTROL ASTERIX Part 9, edition 1.19 (the edition
// Wireshark 4.0 decodes by default). Written per track, in UAP order:
//
//   I062/010 data source           SAC, SIC
//   I062/015 service identification 1 octet
//   I062/070 time of track         24 bits unsigned, LSB 1/128 s, s since midnight UTC
//   I062/105 WGS-84 position       2 × 32 bits two's complement, LSB 180/2^25 deg
//   I062/100 Cartesian position    2 × 24 bits two's complement, LSB 0.5 m
//   I062/185 Cartesian velocity    2 × 16 bits two's complement, LSB 0.25 m/s
//   I062/060 Mode 3/A code         optional; 12-bit octal code, V/G/CH = 0
//   I062/245 target identification optional; STI 0 (downlinked from the target), then 8
//                                  characters of ICAO's 6-bit set (A-Z, 0-9, space)
//   I062/380 aircraft derived data optional; subfield #1 ADR only (24-bit address)
//   I062/040 track number          16 bits
//   I062/080 track status          1 to 4 octets, as far as the flags set need
//   I062/130 geometric altitude    optional; 16 bits two's complement, LSB 6.25 ft
//   I062/500 estimated accuracies  optional; APC (σx, σy: 16 bits, LSB 0.5 m), COV (16 bits
//                                  two's complement, sign(cov)·sqrt|cov|, LSB 0.5 m), ATV
//                                  (σvx, σvy: 8 bits, LSB 0.25 m/s), AGA (8 bits, LSB 6.25 ft)
//
// x, y are the system's local Cartesian plane (the standard leaves its origin to the system),
// y towards geographic north. The decoder reads these items and skips every other item of the
// edition's UAP.

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "skyfuse/asterix/bytes.hpp"
#include "skyfuse/asterix/data_source.hpp"
#include "skyfuse/asterix/record_walker.hpp"

namespace skyfuse::asterix {

inline constexpr std::uint8_t kCat062 = 62;

/// I062/080's flags this library writes and reads; each false is the standard's default value.
struct TrackStatus {
  bool mono_sensor = false;    ///< MON: 1 monosensor, 0 multisensor track
  bool tentative = false;      ///< CNF: 1 tentative, 0 confirmed
  bool simulated = false;      ///< SIM (first extension)
  bool last_message = false;   ///< TSE: last message for the track (first extension)
  bool first_message = false;  ///< TSB: first message for the track (first extension)
  bool coasting = false;       ///< CST: age of the last update above the system's threshold
  bool psr_aged = false;       ///< PSR, SSR, MDS, ADS: age of the last update by that kind of
  bool ssr_aged = false;       ///< sensor above the system's threshold (third extension)
  bool mode_s_aged = false;
  bool adsb_aged = false;
  /// SRC: source of I062/130 (0 none, 1 GNSS, 2 3D radar, 3 triangulation, 4 height from
  /// coverage, 5 speed look-up table, 6 default height, 7 multilateration). MRH is set to
  /// "geometric more reliable" when a geometric altitude is sent.
  std::uint8_t altitude_source = 0;
  bool operator==(const TrackStatus&) const = default;
};

/// Standard deviations (1σ) and the x–y covariance, as I062/500 carries them. Values above
/// a subfield's maximum are sent as the maximum: the standard defines the maximum as "maximum
/// value or above". Negative σ are refused.
struct TrackAccuracy {
  double sigma_x_m = 0.0;       ///< APC X, ≤ 32 767.5 m
  double sigma_y_m = 0.0;       ///< APC Y
  double covariance_xy_m2 = 0;  ///< COV, sent as sign·sqrt(|cov|) in 0.5 m, |.| ≤ 16 383.5 m
  double sigma_vx_mps = 0.0;    ///< ATV X, ≤ 63.75 m/s
  double sigma_vy_mps = 0.0;    ///< ATV Y
  std::optional<double> sigma_altitude_m;  ///< AGA, ≤ 255 × 6.25 ft
};

struct SystemTrack {
  DataSource source;               ///< I062/010
  std::uint8_t service_id = 0;     ///< I062/015
  std::uint16_t track_number = 0;  ///< I062/040
  double time_of_track_s = 0.0;    ///< I062/070, [0, 86400) s since midnight UTC
  TrackStatus status;              ///< I062/080
  double x_m = 0.0;                ///< I062/100, |.| ≤ 4 194 303.5 m
  double y_m = 0.0;
  double latitude_deg = 0.0;   ///< I062/105, [-90, 90]
  double longitude_deg = 0.0;  ///< I062/105, [-180, 180)
  double vx_mps = 0.0;         ///< I062/185, [-8192, 8191.75] m/s
  double vy_mps = 0.0;
  std::optional<std::uint16_t> mode3a;         ///< I062/060, the code's octal digits (07777 max)
  std::optional<std::string> callsign;         ///< I062/245, without its trailing spaces
  std::optional<std::uint32_t> address;        ///< I062/380 ADR, 24 bits
  std::optional<double> geometric_altitude_m;  ///< I062/130, [-1500, 150000] ft
  std::optional<TrackAccuracy> accuracy;       ///< I062/500
};

/// One record (FSPEC and items), or the first item that cannot hold its value.
Encoded encode_cat062_record(const SystemTrack& track);
/// One data block of `tracks`.
Encoded encode_cat062(std::span<const SystemTrack> tracks);

/// The track a walked CAT062 record carries, or why it is refused: value_out_of_range, or
/// missing_item when one of the items a SystemTrack cannot be without (010, 040, 070, 080,
/// 100, 105, 185) is absent. 015 absent reads as service 0; the optional items stay empty.
using Cat062Decoded = RecordOutcome<SystemTrack>;
Cat062Decoded decode_cat062_record(const WalkedRecord& record);

}  // namespace skyfuse::asterix
