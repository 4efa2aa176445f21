#pragma once
/// \file
/// One aircraft, one track: a confirmed track without an address that holds the same aircraft
/// as a confirmed track with one is dropped at a round's close, at every node alike.
///
/// Identity (identity.hpp) joins a primary radar's track and the aircraft's broadcast where the
/// broadcast gates with the radar's track. Where it does not — a 2-D radar's track at the wrong
/// height, a track that lagged in a turn — the broadcast starts a track of its own, and the
/// radar's plots keep the first alive beside it: the aircraft is held twice for as long as both
/// are fed. This rule ends that once the two tracks agree.
///
/// Two tracks hold one aircraft when their positions and velocities differ by no more than their
/// spreads allow: d² = Δᵀ (P₁ + P₂)⁻¹ Δ over [p; v] (the first six entries of every state a
/// picture runs) within the χ²(6) quantile of the tracker's merge probability. The sum leaves
/// out the tracks' correlation (they took the same plots), so d² is, if anything, smaller than
/// the exact test's. The unaddressed track is the one dropped: the aircraft keeps the track
/// that holds its address, which the broadcasts go to. Only confirmed tracks take part: a
/// tentative addressed track may be a spoof's beginning, and a tentative unaddressed one a
/// nearby aircraft's first fixes; an unaddressed track is merged at the close that confirms it.

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "skyfuse/core/types.hpp"
#include "skyfuse/picture/address.hpp"
#include "skyfuse/picture/track.hpp"

namespace skyfuse {

/// The entries the merge test compares: position and velocity.
inline constexpr int kMergeDim = 6;

/// d² = Δᵀ S⁻¹ Δ of a `difference` Δ over [p; v] under the summed `spread` S; +∞ where S is not
/// positive definite (nothing to merge on). Compiled once (track_merge.cpp), whatever the state.
double merge_distance(const Vector<kMergeDim>& difference, const Covariance<kMergeDim>& spread);

/// d² of two estimates' position and velocity under their summed spreads; +∞ where the sum is
/// not positive definite.
template <int N>
double merge_distance(const GaussianState<N>& a, const GaussianState<N>& b) {
  static_assert(N >= kMergeDim, "the merge compares position and velocity");
  return merge_distance(
      Vector<kMergeDim>(a.mean.template head<kMergeDim>() - b.mean.template head<kMergeDim>()),
      Covariance<kMergeDim>(a.covariance.template topLeftCorner<kMergeDim, kMergeDim>() +
                            b.covariance.template topLeftCorner<kMergeDim, kMergeDim>()));
}

/// What find_tracks_held_twice keeps from round to round, so that a round allocates nothing
/// once the picture has grown.
struct MergeWork {
  /// An addressed confirmed track: its east, the trace of its position block, its index.
  struct Holder {
    double east = 0.0;
    double position_spread = 0.0;
    std::size_t index = 0;
  };
  std::vector<Holder> holders;
  /// dropped[t]: whether track t is held twice (the answer).
  std::vector<char> dropped;
};

/// Sets work.dropped[t] for each of `tracks` (picture order, `estimates` theirs): whether it is a
/// confirmed track without an address whose estimate lies within `gate` (merge_distance) of a
/// confirmed track's with an address, one a round's close drops. Returns how many are; none
/// where `gate` ≤ 0 (the merge off).
template <typename TrackType, int N>
std::size_t find_tracks_held_twice(std::span<const TrackType> tracks,
                                   std::span<const GaussianState<N>> estimates, double gate,
                                   MergeWork& work) {
  work.dropped.assign(tracks.size(), 0);
  if (!(gate > 0.0)) return 0;
  // The addressed tracks by east, so that each unaddressed track looks only at those within
  // reach: d² over [p; v] is at least |Δp|² / trace(P₁ + P₂) over the position blocks.
  const auto position_spread = [&](std::size_t t) {
    return estimates[t].covariance.template topLeftCorner<3, 3>().trace();
  };
  std::vector<MergeWork::Holder>& holders = work.holders;
  holders.clear();
  double widest = 0.0;
  for (std::size_t t = 0; t < tracks.size(); ++t) {
    if (tracks[t].status != TrackStatus::kConfirmed || tracks[t].address == kNoAddress) continue;
    holders.push_back({estimates[t].mean(0), position_spread(t), t});
    widest = std::max(widest, holders.back().position_spread);
  }
  if (holders.empty()) return 0;
  std::sort(holders.begin(), holders.end(), [](const auto& a, const auto& b) {
    return a.east < b.east || (a.east == b.east && a.index < b.index);
  });
  std::size_t found = 0;
  for (std::size_t t = 0; t < tracks.size(); ++t) {
    if (tracks[t].status != TrackStatus::kConfirmed || tracks[t].address != kNoAddress) continue;
    const double own = position_spread(t);
    const double reach = std::sqrt(gate * (own + widest));
    const double east = estimates[t].mean(0);
    auto h = std::lower_bound(holders.begin(), holders.end(), east - reach,
                              [](const auto& a, double e) { return a.east < e; });
    for (; h != holders.end() && h->east <= east + reach; ++h) {
      const double apart =
          (estimates[t].mean.template head<3>() - estimates[h->index].mean.template head<3>())
              .squaredNorm();
      if (apart > gate * (own + h->position_spread)) continue;
      if (merge_distance(estimates[t], estimates[h->index]) <= gate) {
        work.dropped[t] = 1;
        ++found;
        break;
      }
    }
  }
  return found;
}

}  // namespace skyfuse
