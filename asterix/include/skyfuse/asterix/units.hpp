#pragma once
// The units ASTERIX items are defined in, against the SI units of skyfuse's structs. Both
// conversions are exact by definition (international foot and nautical mile).

namespace skyfuse::asterix {

inline constexpr double kMetresPerFoot = 0.3048;
inline constexpr double kMetresPerNauticalMile = 1852.0;
inline constexpr double kSecondsPerDay = 86400.0;

}  // namespace skyfuse::asterix
