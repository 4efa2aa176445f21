#pragma once
// The octets of an encoded record or data block, and why an encoder refused to write one.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace skyfuse::asterix {

using Bytes = std::vector<std::uint8_t>;

/// The first value an encoder could not write: the item (e.g. "I062/100 X") and why.
struct EncodeError {
  std::string item;
  std::string reason;
};

/// An encoder's result: the octets, or (bytes empty) the error.
struct Encoded {
  Bytes bytes;
  std::optional<EncodeError> error;
  explicit operator bool() const { return !error.has_value(); }
};

}  // namespace skyfuse::asterix
