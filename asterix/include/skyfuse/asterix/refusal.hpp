#pragma once
// Why a decoder refused bytes, counted by kind.
//
// What a refusal costs (records carry no length of their own, so a record whose end cannot be
// found takes the rest of its block with it):
//   - truncated_block, length_mismatch: the rest of the datagram (its next block cannot be
//     found);
//   - unknown_category: that block (its LEN still leads to the next one);
//   - fspec_past_end, undefined_item, item_truncated, item_malformed: the record and the rest
//     of its block (records read before it are kept);
//   - value_out_of_range, missing_item: that record only (its end is known; decoding goes on
//     with the next record).

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace skyfuse::asterix {

enum class Refusal : std::uint8_t {
  truncated_block,     ///< fewer than 3 octets left for a data block's CAT and LEN
  length_mismatch,     ///< LEN shorter than a block with one record, or past the datagram's end
  unknown_category,    ///< a CAT this decoder does not read (only 021, 048, 062)
  fspec_past_end,      ///< the FSPEC's FX chain runs past the end of the block
  undefined_item,      ///< the FSPEC names a spare FRN or one beyond the category's UAP
  item_truncated,      ///< an item (or one of its extensions, repetitions) runs past the block
  item_malformed,      ///< an item's own structure is wrong (FX past its last extension, ...)
  value_out_of_range,  ///< a value outside the item's range, or a reserved code
  missing_item,        ///< a record without an item the decoder needs (e.g. I062/040)
};
inline constexpr std::size_t kRefusalKinds = 9;

/// The kind's name as summaries print it ("fspec_past_end").
std::string_view refusal_name(Refusal kind);

struct RefusalCounts {
  std::array<std::uint64_t, kRefusalKinds> by_kind{};

  void add(Refusal kind) { ++by_kind[static_cast<std::size_t>(kind)]; }
  std::uint64_t operator[](Refusal kind) const { return by_kind[static_cast<std::size_t>(kind)]; }
  std::uint64_t total() const;
  RefusalCounts& operator+=(const RefusalCounts& other);
};

}  // namespace skyfuse::asterix
