#pragma once
/// \file
/// An aircraft's address, as a cooperative sensor (a Mode S radar, an ADS-B or Remote ID
/// receiver, multilateration) reports it with a detection: its ICAO 24-bit address or a
/// Remote ID serial. What an address decides in the tracker is picture/identity.hpp.

#include <cstddef>
#include <cstdint>
#include <span>

namespace skyfuse {

using Address = std::uint32_t;
/// A detection without an address (a primary radar's, a false alarm), a track that has none.
inline constexpr Address kNoAddress = 0;

/// The address of entry j of `addresses` (per detection or per track), where an empty list
/// means that none has one.
inline Address address_of(std::span<const Address> addresses, std::size_t j) {
  return addresses.empty() ? kNoAddress : addresses[j];
}

/// Which pairs the gate search (hypothesiser.hpp) leaves out because of identity: a track that
/// took a detection of its address, a detection routed to its track or refused, and a pair of
/// an addressed detection with a track holding an address. Empty spans leave nothing out.
struct IdentityMask {
  std::span<const Address> track_addresses;      ///< per track, or empty
  std::span<const Address> detection_addresses;  ///< per detection, or empty
  std::span<const char> track_taken;             ///< per track, or empty
  std::span<const char> detection_decided;       ///< per detection, or empty

  bool skips_track(std::size_t t) const { return !track_taken.empty() && track_taken[t] != 0; }
  bool skips_detection(std::size_t j) const {
    return !detection_decided.empty() && detection_decided[j] != 0;
  }
  /// A pair is skipped when both of these hold: track t holds an address, detection j has one.
  bool holds_address(std::size_t t) const { return address_of(track_addresses, t) != kNoAddress; }
  bool is_addressed(std::size_t j) const {
    return address_of(detection_addresses, j) != kNoAddress;
  }
};

}  // namespace skyfuse
