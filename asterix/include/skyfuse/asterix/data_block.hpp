#pragma once
// The ASTERIX data block: CAT (1 octet), LEN (2 octets, big-endian, counting CAT and LEN
// themselves), then the records of that category back to back. A UDP datagram holds one or
// more blocks.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "skyfuse/asterix/bytes.hpp"
#include "skyfuse/asterix/refusal.hpp"

namespace skyfuse::asterix {

inline constexpr std::size_t kBlockHeaderOctets = 3;
inline constexpr std::size_t kMaxBlockOctets = 65535;  // LEN is 16 bits

/// One block of `category` holding `records`; an error if they exceed LEN's 65 535 octets.
Encoded encode_block(std::uint8_t category, std::span<const Bytes> records);

/// Blocks of `category` holding `records` in order, each at most `max_octets` long (e.g. 1472
/// for one Ethernet frame's UDP payload); an error if one record alone does not fit.
std::vector<Bytes> encode_blocks(std::uint8_t category, std::span<const Bytes> records,
                                 std::size_t max_octets, std::optional<EncodeError>& error);

struct BlockView {
  std::uint8_t category = 0;
  std::span<const std::uint8_t> records;  ///< after LEN, up to LEN's end
};

/// The blocks of a datagram, as far as they are framed right; a framing error (truncated_block,
/// length_mismatch) ends the split and is counted in `refusals`.
std::vector<BlockView> split_blocks(std::span<const std::uint8_t> datagram,
                                    RefusalCounts& refusals);

}  // namespace skyfuse::asterix
