#pragma once
/// \file
/// Counting a refused sample and telling the log about it, rate-limited per kind.

#include <spdlog/spdlog.h>

#include <cstdint>
#include <string_view>

#include "skyfuse/validation/drop_tally.hpp"

namespace skyfuse::transport {

/// Counts one refused sample of `topic` claiming to come from `station_id` at `step`.
inline void count_drop(DropTally& tally, DropKind kind, std::string_view topic, int station_id,
                       std::uint64_t step) {
  if (const std::uint64_t untold = tally.record(kind)) {
    spdlog::warn("dropped {} {} sample(s): {} (latest claims station {}, step {})", untold, topic,
                 to_string(kind), station_id, step);
  }
}

}  // namespace skyfuse::transport
