#include "skyfuse/asterix/datagram.hpp"

#include "skyfuse/asterix/data_block.hpp"
#include "skyfuse/asterix/record_walker.hpp"

namespace skyfuse::asterix {
namespace {

// Every record of one block: a record whose end is unknown ends the block (refusal.hpp); one
// whose value is refused is skipped, and the next one read.
template <typename DecodeRecord, typename Keep>
void decode_records(std::span<const std::uint8_t> records, std::span<const UapEntry> uap,
                    RefusalCounts& refusals, DecodeRecord decode, Keep keep) {
  std::size_t at = 0;
  while (at < records.size()) {
    const auto walked = walk_record(records.subspan(at), uap);
    if (walked.refusal) {
      refusals.add(*walked.refusal);
      return;
    }
    const auto decoded = decode(walked);
    if (decoded.refusal) {
      refusals.add(*decoded.refusal);
    } else {
      keep(decoded);
    }
    at += walked.octets;
  }
}

}  // namespace

void decode_datagram(std::span<const std::uint8_t> datagram, Decoded& into) {
  for (const auto& block : split_blocks(datagram, into.refusals)) {
    switch (block.category) {
      case kCat062:
        decode_records(block.records, uap_cat062(), into.refusals, decode_cat062_record,
                       [&into](const Cat062Decoded& d) { into.tracks.push_back(*d.value); });
        break;
      case kCat048:
        decode_records(block.records, uap_cat048(), into.refusals, decode_cat048_record,
                       [&into](const Cat048Decoded& d) { into.plots.push_back(*d.value); });
        break;
      case kCat021:
        decode_records(block.records, uap_cat021(), into.refusals, decode_cat021_record,
                       [&into](const Cat021Decoded& d) { into.reports.push_back(*d.value); });
        break;
      default:
        into.refusals.add(Refusal::unknown_category);
        break;
    }
  }
}

Decoded decode_datagram(std::span<const std::uint8_t> datagram) {
  Decoded decoded;
  decode_datagram(datagram, decoded);
  return decoded;
}

}  // namespace skyfuse::asterix
