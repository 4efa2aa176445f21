#include "skyfuse/asterix/fspec.hpp"

#include <algorithm>

namespace skyfuse::asterix {

void append_fspec(Bytes& out, std::span<const unsigned> present) {
  unsigned highest = 0;
  for (const auto frn : present) highest = std::max(highest, frn);
  if (highest == 0) {
    out.push_back(0);  // a record names at least its first octet, even if empty
    return;
  }
  const std::size_t octets = (highest + 6) / 7;
  Bytes fspec(octets, 0);
  for (const auto frn : present) {
    if (frn == 0) continue;
    const unsigned index = frn - 1;
    fspec[index / 7] |= static_cast<std::uint8_t>(0x80u >> (index % 7));
  }
  for (std::size_t i = 0; i + 1 < octets; ++i) fspec[i] |= 0x01u;  // FX: another octet follows
  out.insert(out.end(), fspec.begin(), fspec.end());
}

std::optional<Fspec> read_fspec(std::span<const std::uint8_t> bytes) {
  Fspec fspec;
  for (std::size_t i = 0;; ++i) {
    if (i >= bytes.size()) return std::nullopt;
    const std::uint8_t octet = bytes[i];
    for (unsigned bit = 0; bit < 7; ++bit) {
      if ((octet & (0x80u >> bit)) != 0) {
        fspec.present.push_back(static_cast<unsigned>(i * 7 + bit + 1));
      }
    }
    if ((octet & 0x01u) == 0) {
      fspec.octets = i + 1;
      return fspec;
    }
  }
}

}  // namespace skyfuse::asterix
