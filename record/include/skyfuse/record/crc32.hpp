#pragma once
// CRC-32 as MCAP, zip and PNG use it (polynomial 0xEDB88320 reflected, initial and final value
// 0xFFFFFFFF): crc32("123456789") == 0xCBF43926.

#include <cstdint>
#include <string_view>

namespace skyfuse::record {

/// Continues a CRC over `bytes`: crc32(b, crc32(a)) == crc32(a + b); start from 0.
std::uint32_t crc32(std::string_view bytes, std::uint32_t crc = 0);

}  // namespace skyfuse::record
