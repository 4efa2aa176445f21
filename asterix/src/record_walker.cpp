#include "skyfuse/asterix/record_walker.hpp"

#include "skyfuse/asterix/fspec.hpp"

namespace skyfuse::asterix {

WalkedRecord walk_record(std::span<const std::uint8_t> bytes, std::span<const UapEntry> uap) {
  WalkedRecord record;
  const auto fspec = read_fspec(bytes);
  if (!fspec) {
    record.refusal = Refusal::fspec_past_end;
    return record;
  }
  std::size_t at = fspec->octets;
  for (const unsigned frn : fspec->present) {
    if (frn > uap.size() || uap[frn - 1].item == 0) {
      record.refusal = Refusal::undefined_item;
      return record;
    }
    const auto& entry = uap[frn - 1];
    const auto length = item_length(bytes.subspan(at), entry.format);
    if (const auto* refusal = std::get_if<Refusal>(&length)) {
      record.refusal = *refusal;
      return record;
    }
    const auto octets = std::get<std::size_t>(length);
    record.items.push_back({entry.item, bytes.subspan(at, octets)});
    at += octets;
  }
  record.octets = at;
  return record;
}

const ItemBytes* find_item(const WalkedRecord& record, std::uint16_t item) {
  for (const auto& found : record.items) {
    if (found.item == item) return &found;
  }
  return nullptr;
}

bool has_items(const WalkedRecord& record, std::initializer_list<std::uint16_t> items) {
  for (const auto item : items) {
    if (find_item(record, item) == nullptr) return false;
  }
  return true;
}

std::vector<SubfieldBytes> split_compound(std::span<const std::uint8_t> bytes,
                                          std::span<const ItemFormat> subfields) {
  std::vector<SubfieldBytes> present;
  const auto primary = read_fspec(bytes);
  if (!primary) return present;
  std::size_t at = primary->octets;
  for (const unsigned index : primary->present) {
    if (index > subfields.size()) break;
    const auto length = item_length(bytes.subspan(at), subfields[index - 1]);
    if (!std::holds_alternative<std::size_t>(length)) break;
    const auto octets = std::get<std::size_t>(length);
    present.push_back({index, bytes.subspan(at, octets)});
    at += octets;
  }
  return present;
}

}  // namespace skyfuse::asterix
