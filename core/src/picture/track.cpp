#include "skyfuse/picture/track.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace skyfuse {

TrackId make_track_id(std::uint64_t step, int station_id, std::uint32_t detection) {
  if (station_id < 0 || station_id > 0xFFFF || detection > 0xFFFF || step > 0xFFFFFFFFULL) {
    throw std::out_of_range(
        fmt::format("track id: step {}, station {}, detection {} beyond the id's 32/16/16 bits",
                    step, station_id, detection));
  }
  return (step << 32U) | (static_cast<std::uint64_t>(station_id) << 16U) | detection;
}

std::string track_label(TrackId id) {
  return fmt::format("{}.{}.{}", id >> 32U, (id >> 16U) & 0xFFFFU, id & 0xFFFFU);
}

const char* to_string(TrackStatus status) {
  return status == TrackStatus::kConfirmed ? "confirmed" : "tentative";
}

}  // namespace skyfuse
