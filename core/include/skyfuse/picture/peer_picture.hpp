#pragma once
/// \file
/// The fused picture as every peer keeps it. A round:
///  1. every peer predicts every track (TrackTable::predict);
///  2. each station associates its own scan with the predicted tracks (TrackTable::associate:
///     the hypothesiser, then the scenario's associator) and turns each track's pairs into its
///     filter part's contribution against the track's prior (report): what it publishes, with
///     its unassociated detections;
///  3. every peer fuses each track's contributions in ascending station id — a track no
///     station updated is a miss — and closes the round: management, then initiation from
///     every station's unassociated detections (PeerPicture::fuse).
/// Same picture + same reports = same bits at every peer.
///
/// The rounds are defined in peer_picture_impl.hpp and compiled once per filter part and motion
/// model in skyfuse_core (core/src/picture/pictures_shard.cpp); this header declares
/// them.

#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <utility>
#include <variant>
#include <vector>

#include "skyfuse/core/status.hpp"
#include "skyfuse/fusion/station_observation.hpp"
#include "skyfuse/picture/track_table.hpp"

namespace skyfuse {

/// One pair of a station's association as it publishes it: its detection `detection` went to
/// track `track` with `weight` (1 for GNN, the association probability for JPDA).
struct ReportedPair {
  TrackId track = 0;
  std::uint32_t detection = 0;
  double weight = 1.0;
  bool operator==(const ReportedPair&) const = default;
};

/// What a station publishes of a round; `Contribution` is its filter part's for one track.
template <typename Contribution>
struct StationReport {
  struct Update {
    TrackId track = 0;
    /// The station's contribution to the track: its one detection's, or the sum of its
    /// detections' weighed by their pairs' weights.
    Contribution contribution;
    /// The address the station's pairs offer the track (picture/identity.hpp): that of its
    /// detection of weight above 1/2, if it has one; kNoAddress otherwise.
    Address address = kNoAddress;
  };
  int station_id = 0;
  std::vector<Update> updates;      ///< ascending track id
  std::vector<ReportedPair> pairs;  ///< ascending track id, then detection
  /// Each pair's detection as the station measured it, and the σ its report states (empty:
  /// the station's noise), for its registration (both empty where nothing registers).
  std::vector<Detection> paired_detections;
  std::vector<Detection> paired_reported_std;
  /// A registered station's terms for each track it updated, for a filter part whose tracks
  /// keep their cross-covariances with the bias errors (registration/considered_biases.hpp);
  /// ascending track id, empty otherwise.
  struct Considered {
    TrackId track = 0;
    ConsideredTerms terms;
  };
  std::vector<Considered> considered;
  std::vector<UnassociatedDetection> unassociated;  ///< ascending detection index
  std::size_t dropped = 0;            ///< detections beyond the assignment's bound, left out
  std::size_t refused_addresses = 0;  ///< addressed detections refused as possible spoofs
};

/// What a station published of its scan's detections, in scan order: their values, and each
/// one's address and the σ its report states (Scan; each empty where no detection has one).
struct PublishedDetections {
  std::span<const Detection> values;
  std::span<const Address> addresses{};
  std::span<const Detection> reported_std{};
};

template <typename Tracks>
class PeerPicture : public TrackTable<Tracks> {
  using Table = TrackTable<Tracks>;

 public:
  using Contribution = typename Tracks::Contribution;
  using Report = StationReport<Contribution>;
  using Station = typename Table::Station;
  using Table::Table;

  /// Station `station`'s report of `scan` against this (predicted) picture: its association,
  /// each associated track's contribution, its unassociated detections.
  Report report(const Station& station, const Scan& scan, AssociationWork& work) const;

  /// Station `station`'s report rebuilt from what it published (transport/picture_wire.hpp):
  /// its detections (with their addresses and stated σ), its pairs (ascending track id, then
  /// detection) and its unassociated detections' indices, each track's contribution computed here
  /// against this (predicted) picture's track — the station's own arithmetic on the same inputs, so
  /// its bits when this picture is the station's. Nothing when a pair names a track this picture
  /// does not hold: this picture is not the station's. Every index is within `detections` (the
  /// receiver checked it: picture_scan_from_wire).
  std::optional<Report> report_of(const Station& station, const PublishedDetections& detections,
                                  std::span<const ReportedPair> pairs,
                                  std::span<const std::uint32_t> unassociated,
                                  std::size_t dropped) const;

  /// Fuses the round's reports (one per station that reported, ascending station id) and
  /// closes the round. A track whose fusion fails numerically is left as predicted and counts
  /// as a miss.
  RoundOutcome fuse(std::uint64_t step, std::span<const Report> reports);

 private:
  // Adds `track`'s contribution from `station`'s detections `pairs` (all of this track) to
  // `report`, with the pairs that made it (peer_picture_impl.hpp).
  // `Pair`: a WeightedPair (the station's own association) or a ReportedPair (a published one).
  template <typename Pair>
  void add_update(Report& report, const Station& station, const typename Table::TrackType& track,
                  std::span<const Pair> pairs, const PublishedDetections& detections) const;
  // add_update with the station's sensor, `Sensor`, and its noise as they are.
  template <typename Pair, typename Sensor>
  void add_update_of(Report& report, int station_id, const Sensor& sensor,
                     const Covariance<Sensor::kMeasDim>& noise,
                     const typename Table::TrackType& track, std::span<const Pair> pairs,
                     const PublishedDetections& detections) const;
  // For a part whose tracks keep their cross-covariances with the bias errors: the terms of
  // `track`'s update by a registered station from its `pairs` (ConsideredTerms).
  template <typename Sensor>
  void add_considered(Report& report, int station_id, const Sensor& sensor,
                      const Covariance<Sensor::kMeasDim>& noise,
                      const typename Table::TrackType& track,
                      const BiasCorrection<Sensor>& correction, std::span<const ReportedPair> pairs,
                      const PublishedDetections& detections) const;
  double weight_of(int station_id) const;

  std::vector<char> hit_;
  std::vector<std::size_t> cursor_;
  std::vector<double> report_weights_;  // reports[r]'s station's weight
  std::vector<const Contribution*> contributions_;
  std::vector<double> weights_;
  std::vector<std::size_t> considered_cursor_;  // per report: its next Considered
  std::vector<ConsideredTerms> terms_;
  std::vector<double> term_weights_;
  std::vector<Address> offered_;  // per track: the address its hit offers (close_round)
};

}  // namespace skyfuse
