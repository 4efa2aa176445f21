#include "skyfuse/asterix/data_block.hpp"

#include <algorithm>
#include <string>

namespace skyfuse::asterix {
namespace {

void append_header(Bytes& out, std::uint8_t category, std::size_t length) {
  out.push_back(category);
  out.push_back(static_cast<std::uint8_t>(length >> 8 & 0xFFu));
  out.push_back(static_cast<std::uint8_t>(length & 0xFFu));
}

}  // namespace

Encoded encode_block(std::uint8_t category, std::span<const Bytes> records) {
  std::size_t length = kBlockHeaderOctets;
  for (const auto& record : records) length += record.size();
  if (length > kMaxBlockOctets) {
    return {{},
            EncodeError{"data block LEN", "records need " + std::to_string(length) +
                                              " octets, LEN holds at most 65535"}};
  }
  Encoded block;
  block.bytes.reserve(length);
  append_header(block.bytes, category, length);
  for (const auto& record : records) {
    block.bytes.insert(block.bytes.end(), record.begin(), record.end());
  }
  return block;
}

std::vector<Bytes> encode_blocks(std::uint8_t category, std::span<const Bytes> records,
                                 std::size_t max_octets, std::optional<EncodeError>& error) {
  std::vector<Bytes> blocks;
  const std::size_t limit = std::min(max_octets, kMaxBlockOctets);
  std::size_t first = 0;
  std::size_t length = kBlockHeaderOctets;
  for (std::size_t i = 0; i < records.size(); ++i) {
    if (kBlockHeaderOctets + records[i].size() > limit) {
      error =
          EncodeError{"data block LEN",
                      "record " + std::to_string(i) + " of " + std::to_string(records[i].size()) +
                          " octets does not fit a block of " + std::to_string(limit)};
      return {};
    }
    if (length + records[i].size() > limit) {
      blocks.push_back(encode_block(category, records.subspan(first, i - first)).bytes);
      first = i;
      length = kBlockHeaderOctets;
    }
    length += records[i].size();
  }
  if (first < records.size()) {
    blocks.push_back(encode_block(category, records.subspan(first)).bytes);
  }
  return blocks;
}

std::vector<BlockView> split_blocks(std::span<const std::uint8_t> datagram,
                                    RefusalCounts& refusals) {
  std::vector<BlockView> blocks;
  std::size_t at = 0;
  while (at < datagram.size()) {
    const std::size_t left = datagram.size() - at;
    if (left < kBlockHeaderOctets) {
      refusals.add(Refusal::truncated_block);
      break;
    }
    const std::size_t length = std::size_t{datagram[at + 1]} << 8 | datagram[at + 2];
    // A block holds at least one record, and a record at least one FSPEC octet.
    if (length < kBlockHeaderOctets + 1 || length > left) {
      refusals.add(Refusal::length_mismatch);
      break;
    }
    blocks.push_back(
        {datagram[at], datagram.subspan(at + kBlockHeaderOctets, length - kBlockHeaderOctets)});
    at += length;
  }
  return blocks;
}

}  // namespace skyfuse::asterix
