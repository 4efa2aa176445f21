#include "skyfuse/asterix/byte_writer.hpp"

#include <string>

namespace skyfuse::asterix {

void ByteWriter::put(std::uint32_t raw, unsigned octets) {
  for (unsigned i = octets; i-- > 0;) {
    bytes_.push_back(static_cast<std::uint8_t>(raw >> (8 * i) & 0xFFu));
  }
}

void ByteWriter::put_quantity(std::string_view item, double value, double lsb, unsigned octets,
                              Signedness signedness) {
  const unsigned bits = 8 * octets;
  const auto count = quantise(value, lsb, bits, signedness);
  if (!count) {
    fail(item,
         "value " + std::to_string(value) + " does not fit " + std::to_string(bits) +
             (signedness == Signedness::twos_complement ? "-bit signed" : "-bit unsigned") +
             " field of LSB " + std::to_string(lsb),
         octets);  // zeros keep the layout; finish() drops the bytes
    return;
  }
  put(field_bits(*count, bits), octets);
}

void ByteWriter::fail(std::string_view item, std::string_view reason, unsigned pad_octets) {
  if (!error_) error_ = EncodeError{std::string(item), std::string(reason)};
  put(0, pad_octets);
}

Encoded ByteWriter::finish() && {
  if (error_) return Encoded{{}, std::move(error_)};
  return Encoded{std::move(bytes_), std::nullopt};
}

}  // namespace skyfuse::asterix
