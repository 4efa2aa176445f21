#pragma once
// A run of many aircraft's samples as the rogue forges them: a radar's picture scan that passes
// every content check (one detection of a plausible range, azimuth and elevation, left
// unassociated), carrying one fault, for the kinds a scan can carry: another run, a closed or
// far step, an unknown station, a real station's id from the rogue's writer, a value that is not
// finite, a negative range.

#include <cstdint>
#include <vector>

#include "skyfuse/transport/topics.hpp"
#include "skyfuse/validation/drop_kind.hpp"

namespace skyfuse::rogue {

struct ScanAttack {
  DropKind kind;
  wire::PictureScan sample;
};

/// The malformed scans to send when the harness ticks step k of run `run`, impersonating
/// station `victim` (a radar) where an impersonation is the fault.
std::vector<ScanAttack> scan_attacks_at(std::uint64_t run, std::uint32_t k, int victim);

}  // namespace skyfuse::rogue
