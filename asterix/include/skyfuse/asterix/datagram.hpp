#pragma once
// Decoding a UDP datagram of ASTERIX: every block of CAT062, CAT048 and CAT021 in it, record by
// record, with what could not be read counted by kind (refusal.hpp says what each costs).
// Never reads outside the datagram and never throws on its content.

#include <cstdint>
#include <span>
#include <vector>

#include "skyfuse/asterix/cat021.hpp"
#include "skyfuse/asterix/cat048.hpp"
#include "skyfuse/asterix/cat062.hpp"
#include "skyfuse/asterix/refusal.hpp"

namespace skyfuse::asterix {

struct Decoded {
  std::vector<SystemTrack> tracks;
  std::vector<RadarPlot> plots;
  std::vector<AdsbReport> reports;
  RefusalCounts refusals;
};

/// Appends what `datagram` holds to `into` (so one Decoded can gather a whole feed).
void decode_datagram(std::span<const std::uint8_t> datagram, Decoded& into);
Decoded decode_datagram(std::span<const std::uint8_t> datagram);

}  // namespace skyfuse::asterix
