#pragma once
// Data Source Identifier (I062/010, I048/010, I021/010): the System Area Code of the country or
// region and the System Identification Code of the sensor or system within it, one octet each.

#include <cstdint>

namespace skyfuse::asterix {

struct DataSource {
  std::uint8_t sac = 0;
  std::uint8_t sic = 0;
  bool operator==(const DataSource&) const = default;
};

}  // namespace skyfuse::asterix
