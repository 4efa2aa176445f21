#include "skyfuse/transport/picture_callsigns.hpp"

#include <vector>

namespace skyfuse::transport {

void CallsignBook::learn(std::span<const Address> addresses,
                         std::span<const Identification> identifications) {
  if (addresses.empty() || identifications.empty()) return;
  for (std::size_t j = 0; j < addresses.size() && j < identifications.size(); ++j) {
    if (addresses[j] != kNoAddress && identifications[j] != kNoIdentification) {
      entries_[addresses[j]] = identifications[j];
    }
  }
}

Identification CallsignBook::of(Address address) const {
  const auto found = entries_.find(address);
  return found == entries_.end() ? kNoIdentification : found->second;
}

void identify_round(const CallsignBook& book, wire::PictureRound& round) {
  for (wire::PictureTrack& track : round.tracks()) {
    track.identification(book.of(track.address()));
  }
}

void callsigns_to_wire(const CallsignBook& book, wire::PictureState& sample) {
  std::vector<wire::PictureCallsign>& out = sample.callsigns();
  out.clear();
  out.reserve(book.entries().size());
  for (const auto& [address, identification] : book.entries()) {
    wire::PictureCallsign entry;
    entry.address(address);
    entry.identification(identification);
    out.push_back(entry);
  }
}

std::optional<CallsignBook::Entries> callsigns_from_wire(const wire::PictureState& sample) {
  CallsignBook::Entries entries;
  Address previous = kNoAddress;
  for (const wire::PictureCallsign& entry : sample.callsigns()) {
    const bool ascending = entry.address() > previous;  // and so not 0
    if (!ascending || entry.identification() == kNoIdentification ||
        !valid_identification(entry.identification())) {
      return std::nullopt;
    }
    entries.emplace_hint(entries.end(), entry.address(), entry.identification());
    previous = entry.address();
  }
  return entries;
}

}  // namespace skyfuse::transport
