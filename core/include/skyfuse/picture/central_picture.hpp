#pragma once
/// \file
/// The fused picture as the fusion center keeps it, from the raw scans: the same rule as the
/// peers' (peer_picture.hpp) — each station's own association against the center's predicted
/// tracks, with the same hypotheses and associator, then one update per track of the
/// detections associated with it (ascending station id; picture/track_filters.hpp says
/// which), a pair of weight w < 1 (JPDA's) entering with its noise R / w, which weighs its
/// information by w as the peers' weighed sum does; then the same management and initiation. Its
/// prior agrees with the peers' to rounding only, so a pair at a gate's edge could be decided
/// otherwise: the associations are kept for comparison.
///
/// The round is defined in central_picture_impl.hpp and compiled once per filter part and
/// motion model in skyfuse_core (core/src/picture/pictures_shard.cpp); this header
/// declares it.

#include <cstdint>
#include <span>
#include <variant>
#include <vector>

#include "skyfuse/fusion/station_observation.hpp"
#include "skyfuse/picture/track_table.hpp"

namespace skyfuse {

/// One pair a station's assignment made: which of its detections went to which track.
struct Association {
  int station_id = 0;
  std::uint32_t detection = 0;
  TrackId track = 0;
  bool operator==(const Association&) const = default;
  auto operator<=>(const Association&) const = default;
};

template <typename Tracks>
class CentralPicture : public TrackTable<Tracks> {
  using Table = TrackTable<Tracks>;

 public:
  static constexpr int N = Table::kDim;
  using Observation = PictureObservation<N>;
  using Table::Table;

  /// Updates the predicted picture with every station's scan (scans[s] belongs to
  /// stations()[s]) and closes the round.
  RoundOutcome update(std::uint64_t step, std::span<const Scan> scans);

  /// The last round's associations, by station, then track.
  const std::vector<Association>& associations() const { return associations_; }
  /// The last round's addressed detections refused as possible spoofs, every station's.
  std::size_t refused_addresses() const { return refused_addresses_; }

 private:
  // `count` empty lists, keeping the storage of those the last round had: no allocation per
  // round once the picture has its size.
  template <typename T>
  static void clear_each(std::vector<std::vector<T>>& lists, std::size_t count) {
    lists.resize(count);
    for (auto& list : lists) list.clear();
  }

  AssociationWork work_;
  std::vector<Association> associations_;
  std::vector<std::vector<Observation>> observations_;
  std::vector<std::vector<double>> weights_;
  // Per track: its registered stations' observations, for a part whose tracks keep their
  // cross-covariances with the bias errors (ConsidersBiases).
  std::vector<std::vector<ConsideredObservation>> considered_;
  std::vector<std::vector<UnassociatedDetection>> unassociated_;
  std::vector<char> hit_;
  std::vector<Address> offered_;  // per track: the address its pairs offer this round
  std::size_t refused_addresses_ = 0;
};

}  // namespace skyfuse
