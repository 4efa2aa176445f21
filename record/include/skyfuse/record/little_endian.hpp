#pragma once
// Fixed-width integers appended in little-endian byte order, as MCAP records and the Foxglove
// WebSocket protocol's binary frames lay them out.

#include <cstddef>
#include <cstdint>
#include <string>

namespace skyfuse::record {

template <typename T>
void append_little_endian(std::string& out, T value) {
  for (std::size_t i = 0; i < sizeof(T); ++i) {
    out.push_back(static_cast<char>(static_cast<std::uint64_t>(value) >> (8 * i) & 0xFFu));
  }
}

}  // namespace skyfuse::record
