#include "identification.hpp"

#include <cstdint>

namespace skyfuse::asterix::fields {
namespace {

constexpr std::uint8_t kSpace = 32;

// A character's 6-bit code, or nullopt outside the set.
std::optional<std::uint8_t> code_of(char c) {
  if (c >= 'A' && c <= 'Z') return static_cast<std::uint8_t>(c - 'A' + 1);
  if (c >= '0' && c <= '9') return static_cast<std::uint8_t>(c);  // 48-57, as in ASCII
  if (c == ' ') return kSpace;
  return std::nullopt;
}

std::optional<char> char_of(std::uint32_t code) {
  if (code >= 1 && code <= 26) return static_cast<char>('A' + code - 1);
  if (code >= 48 && code <= 57) return static_cast<char>(code);
  if (code == kSpace) return ' ';
  return std::nullopt;
}

}  // namespace

void put_identification(ByteWriter& out, std::string_view item, std::string_view callsign) {
  if (callsign.empty() || callsign.size() > kIdentificationLength ||
      callsign.find_first_not_of(' ') == std::string_view::npos) {
    out.fail(item, "an identification holds 1 to 8 characters, not all spaces", 6);
    return;
  }
  // Two halves of four characters, 24 bits each.
  std::uint32_t halves[2] = {0, 0};
  for (std::size_t i = 0; i < kIdentificationLength; ++i) {
    const auto code = i < callsign.size() ? code_of(callsign[i]) : kSpace;
    if (!code) {
      out.fail(item, std::string("character '") + callsign[i] + "' is not in ICAO's 6-bit set", 6);
      return;
    }
    halves[i / 4] = halves[i / 4] << 6 | *code;
  }
  out.put(halves[0], 3);
  out.put(halves[1], 3);
}

std::optional<std::string> get_identification(ByteReader& in) {
  std::string callsign;
  for (int half = 0; half < 2; ++half) {
    const std::uint32_t bits = in.get(3);
    for (int shift = 18; shift >= 0; shift -= 6) {
      const auto c = char_of(bits >> shift & 0x3Fu);
      if (!c) return std::nullopt;
      callsign.push_back(*c);
    }
  }
  callsign.erase(callsign.find_last_not_of(' ') + 1);
  return callsign;
}

}  // namespace skyfuse::asterix::fields
