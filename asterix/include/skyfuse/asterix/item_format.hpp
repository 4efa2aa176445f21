#pragma once
// The shape of an ASTERIX data item, as much as it takes to find where the item ends without
// understanding it: a decoder skips the items it does not read with these, and checks the
// length of those it does before reading a field.

#include <cstddef>
#include <cstdint>
#include <span>
#include <variant>

#include "skyfuse/asterix/refusal.hpp"

namespace skyfuse::asterix {

struct ItemFormat {
  enum class Kind : std::uint8_t {
    spare,          ///< an FRN the UAP leaves unused: a record that sets it is refused
    fixed,          ///< `octets` octets
    extended,       ///< 1-octet parts, FX (bit 1) set when another follows; at most `octets`
    repetitive,     ///< a REP octet, then REP elements of `octets` each
    repetitive_fx,  ///< elements of `octets` each, FX in the last octet's bit 1 of each
    explicit_len,   ///< a LEN octet counting itself (RE, SP)
    compound,       ///< an FSPEC-like primary subfield, then the present `subfields`
  };
  Kind kind = Kind::spare;
  std::uint8_t octets = 0;
  std::span<const ItemFormat> subfields{};
};

/// The octets the item of `format` at the start of `bytes` occupies, or why it cannot be
/// measured (item_truncated, item_malformed, undefined_item for a compound's spare subfield).
std::variant<std::size_t, Refusal> item_length(std::span<const std::uint8_t> bytes,
                                               const ItemFormat& format);

}  // namespace skyfuse::asterix
