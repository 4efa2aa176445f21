#include "skyfuse/asterix/refusal.hpp"

namespace skyfuse::asterix {

std::string_view refusal_name(Refusal kind) {
  switch (kind) {
    case Refusal::truncated_block:
      return "truncated_block";
    case Refusal::length_mismatch:
      return "length_mismatch";
    case Refusal::unknown_category:
      return "unknown_category";
    case Refusal::fspec_past_end:
      return "fspec_past_end";
    case Refusal::undefined_item:
      return "undefined_item";
    case Refusal::item_truncated:
      return "item_truncated";
    case Refusal::item_malformed:
      return "item_malformed";
    case Refusal::value_out_of_range:
      return "value_out_of_range";
    case Refusal::missing_item:
      return "missing_item";
  }
  return "unknown";
}

std::uint64_t RefusalCounts::total() const {
  std::uint64_t sum = 0;
  for (const auto n : by_kind) sum += n;
  return sum;
}

RefusalCounts& RefusalCounts::operator+=(const RefusalCounts& other) {
  for (std::size_t i = 0; i < kRefusalKinds; ++i) by_kind[i] += other.by_kind[i];
  return *this;
}

}  // namespace skyfuse::asterix
