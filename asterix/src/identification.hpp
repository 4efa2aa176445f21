#pragma once
// A target identification, as I021/170, I062/245 (after its STI octet) and I048/240 carry it:
// eight characters of ICAO's 6-bit set (Annex 10, vol. IV, table 3-9: A-Z as 1-26, space as
// 32, 0-9 as 48-57), left-justified and padded with spaces, 48 bits, the first character in
// the most significant six. Internal to the library.

#include <optional>
#include <string>
#include <string_view>

#include "skyfuse/asterix/byte_reader.hpp"
#include "skyfuse/asterix/byte_writer.hpp"

namespace skyfuse::asterix::fields {

/// The most characters an identification holds.
inline constexpr std::size_t kIdentificationLength = 8;

/// `callsign` (1 to 8 of A-Z, 0-9 and space, not all spaces) in 6 octets; refused otherwise
/// (a lower-case letter included: the set has none).
void put_identification(ByteWriter& out, std::string_view item, std::string_view callsign);

/// The identification of the next 6 octets without its trailing spaces; nullopt where a
/// character's code is outside the set. Eight spaces read as "" (no identification).
std::optional<std::string> get_identification(ByteReader& in);

}  // namespace skyfuse::asterix::fields
