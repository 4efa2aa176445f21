#pragma once
// Appends big-endian fields (ASTERIX sends the most significant octet first) and keeps the
// first error: an encoder writes every item, then asks once whether all of it fitted.

#include <cstdint>
#include <optional>
#include <string_view>

#include "skyfuse/asterix/bytes.hpp"
#include "skyfuse/asterix/quantity.hpp"

namespace skyfuse::asterix {

class ByteWriter {
 public:
  /// `octets` (1..4) octets of `raw`, most significant first; bits above them must be zero.
  void put(std::uint32_t raw, unsigned octets);
  /// `value` as a count of `lsb` in a field of `octets` whole octets; refused (first error
  /// kept) when quantise refuses it. `item` names the field in the error.
  void put_quantity(std::string_view item, double value, double lsb, unsigned octets,
                    Signedness signedness);
  /// Records an error the encoder found itself (a packed field, a code out of range), and
  /// writes `pad_octets` zeros in place of the field so that later fields keep their places.
  void fail(std::string_view item, std::string_view reason, unsigned pad_octets = 0);

  bool ok() const { return !error_.has_value(); }
  const Bytes& bytes() const { return bytes_; }
  /// The octets written, or the first error (then no octets).
  Encoded finish() &&;

 private:
  Bytes bytes_;
  std::optional<EncodeError> error_;
};

}  // namespace skyfuse::asterix
