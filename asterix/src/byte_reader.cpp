#include "skyfuse/asterix/byte_reader.hpp"

namespace skyfuse::asterix {

std::uint32_t ByteReader::get(unsigned octets) {
  if (octets > remaining()) {
    overrun_ = true;
    at_ = bytes_.size();
    return 0;
  }
  std::uint32_t value = 0;
  for (unsigned i = 0; i < octets; ++i) value = value << 8 | bytes_[at_++];
  return value;
}

void ByteReader::skip(std::size_t octets) {
  take(octets);
}

std::span<const std::uint8_t> ByteReader::take(std::size_t octets) {
  if (octets > remaining()) {
    overrun_ = true;
    at_ = bytes_.size();
    return {};
  }
  const auto part = bytes_.subspan(at_, octets);
  at_ += octets;
  return part;
}

}  // namespace skyfuse::asterix
