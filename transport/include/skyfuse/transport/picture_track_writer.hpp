#pragma once
/// \file
/// A node's picture on `skyfuse_track`, for readers outside the run (a viewer, a client of
/// another DDS implementation: docs/interop.md): every track of the picture after each round is
/// a TrackEstimate of its own instance (track id, source), with its status and the stations
/// that updated it last, and a track the picture dropped is unregistered, which readers see as
/// its instance disposed. The run itself reads the whole picture from wire::PictureRound.
///
/// Only while a reader is matched: a write costs the node about 2.5 us a track even with no
/// reader (N = 1 000, M = 8: 2.3-2.6 -> 3.2-3.5 ms of CPU a station-round, docs/picture.md),
/// which a run nobody watches this way should not pay. A reader that joins gets every track
/// at the next round; when the last reader leaves, every track written is unregistered, so
/// that the next reader is not handed stale ones from the writer's history.

#include <cstdint>
#include <utility>
#include <vector>

#include "skyfuse/asterix/track_numbers.hpp"
#include "skyfuse/picture/track.hpp"
#include "skyfuse/picture/track_filters.hpp"
#include "skyfuse/transport/dds_node.hpp"
#include "skyfuse/transport/wire_conversion.hpp"

namespace skyfuse::transport {

class PictureTrackWriter {
 public:
  explicit PictureTrackWriter(DdsNode& node)
      : writer_(node.make_writer<wire::TrackEstimate>({}, kPictureTrackProfile)) {}

  /// Writes `table`'s tracks after round `step` (a TrackTable, a peer's or the center's), each
  /// with its short number in `numbers` (the node's, updated with this round's tracks), and
  /// unregisters those written before that it no longer holds; with no reader matched, writes
  /// none and unregisters every one written before.
  template <typename Table>
  void publish(const Table& table, const asterix::TrackNumbers& numbers, std::uint64_t run_id,
               std::uint32_t step, int source_id, wire::TrackSource mode) {
    constexpr int N = Table::kDim;
    const auto tracks = table.tracks();
    std::vector<TrackId>& now = writing_;
    now.clear();
    if (writer_.matched() > 0) {
      for (std::size_t t = 0; t < tracks.size(); ++t) now.push_back(tracks[t].id);
    }
    // Both lists ascend (a table keeps its tracks by id): the dropped ones in one pass.
    std::size_t kept = 0;
    for (const TrackId id : written_) {
      while (kept < now.size() && now[kept] < id) ++kept;
      if (kept < now.size() && now[kept] == id) continue;
      wire::TrackEstimate gone;
      gone.track_id(id);
      gone.source_id(source_id);
      writer_.unregister(gone);
    }
    for (std::size_t t = 0; t < now.size(); ++t) {
      wire::TrackEstimate sample =
          to_wire<N>(table.estimates()[t], run_id, step, source_id, mode, tracks[t].updated_by);
      sample.track_id(tracks[t].id);
      sample.track_number(numbers.number_of(tracks[t].id).value_or(0));
      sample.confirmed(tracks[t].status == TrackStatus::kConfirmed);
      if constexpr (ImmTrackState<typename Table::State>) {
        const auto& p = tracks[t].filter.filter().mode_probabilities();
        sample.mode_probabilities(std::vector<double>(p.data(), p.data() + p.size()));
      }
      writer_.write(sample);
    }
    std::swap(written_, writing_);
  }

 private:
  Writer<wire::TrackEstimate> writer_;
  std::vector<TrackId> written_;  // ascending: the tracks of the last round written
  std::vector<TrackId> writing_;  // this round's, kept to reuse its storage
};

}  // namespace skyfuse::transport
