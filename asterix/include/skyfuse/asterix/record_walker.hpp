#pragma once
// Splits one record of a data block into its items: reads the FSPEC, then measures every item
// it names with the UAP's item formats. A category's decoder then reads only whole items.

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <span>
#include <vector>

#include "skyfuse/asterix/refusal.hpp"
#include "skyfuse/asterix/uap.hpp"

namespace skyfuse::asterix {

struct ItemBytes {
  std::uint16_t item = 0;
  std::span<const std::uint8_t> bytes;  ///< the whole item, compound primary included
};

struct WalkedRecord {
  std::size_t octets = 0;          ///< the record's length, FSPEC included (valid if no refusal)
  std::vector<ItemBytes> items;    ///< in FRN order
  std::optional<Refusal> refusal;  ///< set: the record's end is unknown
};

/// The record that starts at `bytes` (which ends where its block ends).
WalkedRecord walk_record(std::span<const std::uint8_t> bytes, std::span<const UapEntry> uap);

/// What a category's decoder made of a walked record: the value, or why it was refused.
template <typename T>
struct RecordOutcome {
  std::optional<T> value;
  std::optional<Refusal> refusal;
};

/// The item `item` of a walked record, if present.
const ItemBytes* find_item(const WalkedRecord& record, std::uint16_t item);
/// Whether every one of `items` is present.
bool has_items(const WalkedRecord& record, std::initializer_list<std::uint16_t> items);

/// A compound item's present subfields: index (1-based) and bytes, in order. `bytes` is a
/// whole item as walk_record measured it, so every subfield is there.
struct SubfieldBytes {
  unsigned index = 0;
  std::span<const std::uint8_t> bytes;
};
std::vector<SubfieldBytes> split_compound(std::span<const std::uint8_t> bytes,
                                          std::span<const ItemFormat> subfields);

}  // namespace skyfuse::asterix
