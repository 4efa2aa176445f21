#pragma once
/// \file
/// When a track is confirmed and when it is deleted: M hits in the last N rounds confirm a
/// tentative track (default 2 of 3, as MATLAB's trackerGNN), a tentative track that can no
/// longer reach M of N is deleted, a confirmed one after K misses in a row (default 5) or once
/// its position is too uncertain to mean anything.

#include <algorithm>

#include "skyfuse/picture/track.hpp"
#include "skyfuse/picture/tracker_config.hpp"

namespace skyfuse {

/// What a round's management decided for a track.
enum class TrackFate { kKept, kConfirmed, kDeleted };

/// Records the round (hit or miss) in a track's `history` and decides its fate from it, its
/// `status` and its position variance (the trace of its estimate's position block); a
/// confirmed track has its status set.
inline TrackFate manage_track(TrackHistory& history, TrackStatus& status, double position_variance,
                              bool hit, const ManagementConfig& config) {
  history.record(hit);
  if (!(position_variance <= config.max_position_std_m * config.max_position_std_m)) {
    return TrackFate::kDeleted;
  }
  if (status == TrackStatus::kConfirmed) {
    return history.consecutive_misses() >= config.delete_misses ? TrackFate::kDeleted
                                                                : TrackFate::kKept;
  }
  const int rounds = std::min(history.rounds(), config.confirm_window);
  const int hits = history.hits_in_last(config.confirm_window);
  if (hits >= config.confirm_hits) {
    status = TrackStatus::kConfirmed;
    return TrackFate::kConfirmed;
  }
  // The hits it can still get before its window is full, or deleted for good.
  const int still_possible = hits + (config.confirm_window - rounds);
  return still_possible >= config.confirm_hits && rounds < config.confirm_window
             ? TrackFate::kKept
             : TrackFate::kDeleted;
}

}  // namespace skyfuse
