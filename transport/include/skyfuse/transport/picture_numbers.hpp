#pragma once
/// \file
/// A node's short track numbers (asterix/track_numbers.hpp): given to its picture's tracks each
/// round, by the same rule at every node, and sent in the whole picture a peer takes
/// (wire::PictureState), so that a station that restarts numbers the next rounds as its peers
/// do. The node's picture to the harness (wire::PictureRound), its CAT062 (`--asterix-out`) and
/// its tracks on `skyfuse_track` carry them.

#include <cstdint>
#include <optional>
#include <vector>

#include "skyfuse/asterix/track_numbers.hpp"
#include "skyfuse/wire/skyfuse_picture.h"

namespace skyfuse::transport {

/// Numbers round k's tracks of `table` (a TrackTable: ascending id) by `numbers`' rule. `ids` is
/// the caller's to keep between rounds, so that a node's round allocates nothing for it.
template <typename Table>
void number_picture(asterix::TrackNumbers& numbers, const Table& table, std::uint64_t k,
                    std::vector<std::uint64_t>& ids) {
  ids.clear();
  for (const auto& track : table.tracks()) ids.push_back(track.id);
  numbers.update(ids, k);
}

/// Each track of `round` given its number in `numbers` (0 where it holds none): what the node's
/// CAT062 sends and the harness records and labels.
void number_round(const asterix::TrackNumbers& numbers, wire::PictureRound& round);

/// `numbers`' state into `sample`.
void track_numbers_to_wire(const asterix::TrackNumbers& numbers, wire::PictureState& sample);

/// The numbering a PictureState carries, or nothing where it is wrong: a number 0, track ids or
/// free numbers not strictly ascending, held numbers not by ascending round, a number given to
/// two tracks, a first never-given number of 0.
std::optional<asterix::TrackNumbers::State> track_numbers_from_wire(
    const wire::PictureState& sample);

}  // namespace skyfuse::transport
