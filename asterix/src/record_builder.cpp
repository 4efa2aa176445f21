#include "record_builder.hpp"

#include <string>

namespace skyfuse::asterix {

ByteWriter& RecordBuilder::item(std::uint16_t item) {
  const unsigned frn = frn_of(uap_, item);
  if (frn == 0 || (!frns_.empty() && frn <= frns_.back())) {
    std::string name = "I";  // appended, not concatenated: GCC 12 warns falsely (-Wrestrict)
    name += std::to_string(item);
    body_.fail(name, "not in the UAP, or out of FRN order");
  }
  frns_.push_back(frn);
  return body_;
}

Encoded RecordBuilder::finish() && {
  auto body = std::move(body_).finish();
  if (!body) return body;
  Encoded record;
  append_fspec(record.bytes, frns_);
  record.bytes.insert(record.bytes.end(), body.bytes.begin(), body.bytes.end());
  return record;
}

}  // namespace skyfuse::asterix
