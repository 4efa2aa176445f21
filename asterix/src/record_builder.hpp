#pragma once
// Builds one record: the encoder opens each item it writes, in UAP order, and writes its
// fields; finish() puts the FSPEC of the items opened in front of them.

#include <cstdint>
#include <span>
#include <vector>

#include "skyfuse/asterix/byte_writer.hpp"
#include "skyfuse/asterix/data_block.hpp"
#include "skyfuse/asterix/fspec.hpp"
#include "skyfuse/asterix/uap.hpp"

namespace skyfuse::asterix {

class RecordBuilder {
 public:
  explicit RecordBuilder(std::span<const UapEntry> uap) : uap_(uap) {}

  /// Opens `item` and returns the writer its fields go to. Items must come in ascending FRN
  /// order, each once (a logic error in the encoder otherwise, reported as an EncodeError).
  ByteWriter& item(std::uint16_t item);

  Encoded finish() &&;

 private:
  std::span<const UapEntry> uap_;
  std::vector<unsigned> frns_;
  ByteWriter body_;
};

/// One data block of `category` holding the record `encode_record` makes of each value, or the
/// first value's error.
template <typename T, typename EncodeRecord>
Encoded encode_block_of(std::uint8_t category, std::span<const T> values,
                        EncodeRecord encode_record) {
  std::vector<Bytes> records;
  records.reserve(values.size());
  for (const auto& value : values) {
    auto record = encode_record(value);
    if (!record) return record;
    records.push_back(std::move(record.bytes));
  }
  return encode_block(category, records);
}

}  // namespace skyfuse::asterix
