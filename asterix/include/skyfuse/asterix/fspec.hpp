#pragma once
// The Field Specification that opens every ASTERIX record: one bit per Field Reference Number
// (FRN) of the category's User Application Profile, seven to an octet (bit 8 of the first octet
// is FRN 1), and bit 1 of each octet (FX) set when another FSPEC octet follows. The same layout
// opens a compound item (its primary subfield), with subfields in place of FRNs.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "skyfuse/asterix/bytes.hpp"

namespace skyfuse::asterix {

/// Appends the FSPEC of the FRNs in `present` (1-based, any order, repeats allowed): as many
/// octets as the highest FRN needs, FX set on all but the last.
void append_fspec(Bytes& out, std::span<const unsigned> present);

/// The FRNs (1-based, ascending) an FSPEC at the start of `bytes` sets, and its length in
/// octets; std::nullopt if its FX chain runs past the end of `bytes`.
struct Fspec {
  std::vector<unsigned> present;
  std::size_t octets = 0;
};
std::optional<Fspec> read_fspec(std::span<const std::uint8_t> bytes);

}  // namespace skyfuse::asterix
