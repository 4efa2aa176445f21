#pragma once
/// \file
/// The callsigns a node learns for the aircraft's addresses (picture/identification.hpp): from
/// every scan of the round it fused, by ascending station id, the newest a detection gives for
/// its address replacing the one before. Every peer fuses the same scans, so every peer holds
/// the same book and names the same tracks alike; the whole picture a parted or restarted peer
/// takes carries it (wire::PictureState). The node's picture to the harness
/// (wire::PictureTrack::identification) and its CAT062 (I062/245) carry each addressed track's.

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <span>

#include "skyfuse/picture/address.hpp"
#include "skyfuse/picture/identification.hpp"
#include "skyfuse/transport/picture_wire.hpp"
#include "skyfuse/wire/skyfuse_picture.h"

namespace skyfuse::transport {

class CallsignBook {
 public:
  using Entries = std::map<Address, Identification>;

  /// Learns each addressed detection's callsign: `addresses` and `identifications` per
  /// detection (either empty when none has one).
  void learn(std::span<const Address> addresses, std::span<const Identification> identifications);
  /// The callsign learnt for `address`; kNoIdentification where none was (or no address).
  Identification of(Address address) const;

  const Entries& entries() const { return entries_; }
  void restore(Entries entries) { entries_ = std::move(entries); }

 private:
  Entries entries_;
};

/// Learns from every scan `scans` holds of the current round (a PictureRoundScans or
/// PictureScans: ascending station id).
template <typename Scans>
void learn_round(CallsignBook& book, const Scans& scans) {
  for (const int id : scans.station_ids()) {
    if (const ReceivedScan* scan = scans.scan_of(id)) {
      book.learn(scan->addresses, scan->identifications);
    }
  }
}

/// Each track of `round` given the callsign `book` holds for its address.
void identify_round(const CallsignBook& book, wire::PictureRound& round);

/// `book` into `sample`.
void callsigns_to_wire(const CallsignBook& book, wire::PictureState& sample);

/// The book a PictureState carries, or nothing where it is wrong: addresses not strictly
/// ascending, an address 0, or an identification that is none or no callsign.
std::optional<CallsignBook::Entries> callsigns_from_wire(const wire::PictureState& sample);

}  // namespace skyfuse::transport
