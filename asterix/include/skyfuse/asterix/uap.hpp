#pragma once
// The User Application Profiles this library reads: for each FRN (index 0 is FRN 1) the item's
// number and shape. Editions are the ones Wireshark 4.0 decodes by default: CAT062 ed. 1.19,
// CAT048 ed. 1.31, CAT021 ed. 2.6 (EUROCONTROL "ASTERIX Part 9 / Part 4 / Part 12").

#include <cstdint>
#include <span>

#include "skyfuse/asterix/item_format.hpp"

namespace skyfuse::asterix {

/// Item numbers as the standard writes them (62/100 is 100); the Reserved Expansion and
/// Special Purpose fields, which have none, take these.
inline constexpr std::uint16_t kReservedExpansion = 1001;
inline constexpr std::uint16_t kSpecialPurpose = 1002;

struct UapEntry {
  std::uint16_t item = 0;  ///< 0: a spare FRN
  ItemFormat format;
};

std::span<const UapEntry> uap_cat062();
std::span<const UapEntry> uap_cat048();
std::span<const UapEntry> uap_cat021();

/// The FRN (1-based) of `item` in `uap`; 0 if the UAP has no such item.
unsigned frn_of(std::span<const UapEntry> uap, std::uint16_t item);

}  // namespace skyfuse::asterix
