#pragma once
/// \file
/// An aircraft's identification: the callsign (or registration) a cooperative sensor reports
/// with its address — an ADS-B broadcast's, a Mode S radar's downlinked one. Air traffic's
/// formats hold up to 8 characters of ICAO's 6-bit set (A-Z, 0-9, space), so one fits a
/// 64-bit word: its characters' ASCII codes, the first in the most significant octet, padded
/// with zero octets. Nothing in the tracker depends on it; it goes where the address goes.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace skyfuse {

using Identification = std::uint64_t;
/// A detection or an aircraft without a callsign.
inline constexpr Identification kNoIdentification = 0;

/// `callsign` as an Identification: 1 to 8 of A-Z, 0-9 and space after its trailing spaces
/// are dropped; lower-case letters are taken as upper case (OpenSky's files hold either).
/// Nothing for anything else, or for a callsign of spaces only.
inline std::optional<Identification> identification_of(std::string_view callsign) {
  while (!callsign.empty() && callsign.back() == ' ') callsign.remove_suffix(1);
  if (callsign.empty() || callsign.size() > 8) return std::nullopt;
  Identification packed = 0;
  for (std::size_t i = 0; i < 8; ++i) {
    char c = i < callsign.size() ? callsign[i] : '\0';
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
    const bool valid = c == '\0' || c == ' ' || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
    if (!valid) return std::nullopt;
    packed = packed << 8 | static_cast<std::uint8_t>(c);
  }
  return packed;
}

/// The callsign `identification` holds, without padding ("" for kNoIdentification).
inline std::string callsign_of(Identification identification) {
  std::string callsign;
  for (int shift = 56; shift >= 0; shift -= 8) {
    const auto c = static_cast<char>(identification >> shift & 0xFFU);
    if (c == '\0') break;
    callsign.push_back(c);
  }
  return callsign;
}

/// Whether `identification` is one identification_of gives, or kNoIdentification: upper-case
/// letters, digits and spaces, then zero octets only, not ending in a space.
inline bool valid_identification(Identification identification) {
  if (identification == kNoIdentification) return true;
  const std::string callsign = callsign_of(identification);
  const auto packed = identification_of(callsign);
  return packed && *packed == identification && callsign.back() != ' ';
}

/// The identification of entry j of `identifications` (per detection), where an empty list
/// means that none has one.
inline Identification identification_at(std::span<const Identification> identifications,
                                        std::size_t j) {
  return identifications.empty() ? kNoIdentification : identifications[j];
}

}  // namespace skyfuse
