#include "skyfuse/asterix/item_format.hpp"

#include "skyfuse/asterix/fspec.hpp"

namespace skyfuse::asterix {
namespace {

using Kind = ItemFormat::Kind;
using Length = std::variant<std::size_t, Refusal>;

// An extended item: 1-octet parts while FX (bit 1) is set, at most `max_parts` of them.
Length extended_length(std::span<const std::uint8_t> bytes, std::size_t max_parts) {
  for (std::size_t i = 0;; ++i) {
    if (i >= bytes.size()) return Refusal::item_truncated;
    if ((bytes[i] & 0x01u) == 0) return i + 1;
    if (i + 1 >= max_parts) return Refusal::item_malformed;  // FX set on the last extension
  }
}

Length repetitive_fx_length(std::span<const std::uint8_t> bytes, std::size_t element) {
  if (element == 0) return Refusal::item_malformed;
  for (std::size_t end = element;; end += element) {
    if (end > bytes.size()) return Refusal::item_truncated;
    if ((bytes[end - 1] & 0x01u) == 0) return end;
  }
}

Length compound_length(std::span<const std::uint8_t> bytes, std::span<const ItemFormat> subfields) {
  const auto primary = read_fspec(bytes);
  if (!primary) return Refusal::item_truncated;
  std::size_t length = primary->octets;
  for (const unsigned index : primary->present) {
    if (index > subfields.size() || subfields[index - 1].kind == Kind::spare ||
        subfields[index - 1].kind == Kind::compound) {
      return Refusal::undefined_item;
    }
    const auto sub = item_length(bytes.subspan(length), subfields[index - 1]);
    if (std::holds_alternative<Refusal>(sub)) return sub;
    length += std::get<std::size_t>(sub);
  }
  return length;
}

}  // namespace

Length item_length(std::span<const std::uint8_t> bytes, const ItemFormat& format) {
  switch (format.kind) {
    case Kind::spare:
      return Refusal::undefined_item;
    case Kind::fixed:
      if (bytes.size() < format.octets) return Refusal::item_truncated;
      return std::size_t{format.octets};
    case Kind::extended:
      return extended_length(bytes, format.octets);
    case Kind::repetitive: {
      if (bytes.empty()) return Refusal::item_truncated;
      const std::size_t length = 1 + std::size_t{bytes[0]} * format.octets;
      if (bytes.size() < length) return Refusal::item_truncated;
      return length;
    }
    case Kind::repetitive_fx:
      return repetitive_fx_length(bytes, format.octets);
    case Kind::explicit_len: {
      if (bytes.empty()) return Refusal::item_truncated;
      const std::size_t length = bytes[0];
      if (length == 0) return Refusal::item_malformed;  // LEN counts itself: at least 1
      if (bytes.size() < length) return Refusal::item_truncated;
      return length;
    }
    case Kind::compound:
      return compound_length(bytes, format.subfields);
  }
  return Refusal::item_malformed;
}

}  // namespace skyfuse::asterix
