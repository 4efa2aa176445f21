#pragma once
// Reads big-endian fields from a span it never leaves: a read past the end returns zero and
// marks the reader overrun, so that a decoder checks once, after reading an item, instead of
// before every field.

#include <cstddef>
#include <cstdint>
#include <span>

namespace skyfuse::asterix {

class ByteReader {
 public:
  explicit ByteReader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}

  /// `octets` (1..4) octets, most significant first; 0 and overrun() if fewer remain.
  std::uint32_t get(unsigned octets);
  /// Skips `octets`; overrun() if fewer remain (then the reader stands at the end).
  void skip(std::size_t octets);
  /// The next `octets` as a span, advancing past them; empty and overrun() if fewer remain.
  std::span<const std::uint8_t> take(std::size_t octets);

  std::size_t position() const { return at_; }
  std::size_t remaining() const { return bytes_.size() - at_; }
  bool overrun() const { return overrun_; }

 private:
  std::span<const std::uint8_t> bytes_;
  std::size_t at_ = 0;
  bool overrun_ = false;
};

}  // namespace skyfuse::asterix
