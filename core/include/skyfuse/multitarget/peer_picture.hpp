#pragma once
/// \file
/// The fused picture as every peer keeps it. A round:
///  1. every peer predicts every track (TrackTable::predict);
///  2. each station assigns its own scan to the predicted tracks and turns each pair into its
///     filter part's contribution against the track's prior (station_report): what it
///     publishes, with its unassociated detections;
///  3. every peer fuses each track's contributions in ascending station id — a track no
///     station updated is a miss — and closes the round: management, then initiation from
///     every station's unassociated detections (PeerPicture::fuse).
/// Same picture + same reports = same bits at every peer.

#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "skyfuse/core/status.hpp"
#include "skyfuse/fusion/station_observation.hpp"
#include "skyfuse/multitarget/track_table.hpp"

namespace skyfuse {

/// What a station publishes of a round; `Contribution` is its filter part's for one track.
template <typename Contribution, int M>
struct StationReport {
  struct Update {
    TrackId track = 0;
    std::uint32_t detection = 0;
    Contribution contribution;
  };
  int station_id = 0;
  std::vector<Update> updates;                         ///< ascending track id
  std::vector<UnassociatedDetection<M>> unassociated;  ///< ascending detection index
  std::size_t dropped = 0;  ///< detections beyond the assignment's bound, left out
};

template <typename Tracks, typename Sensor>
class PeerPicture : public TrackTable<Tracks, Sensor> {
  using Table = TrackTable<Tracks, Sensor>;

 public:
  using Contribution = typename Tracks::Contribution;
  using Report = StationReport<Contribution, Sensor::kMeasDim>;
  using Table::Table;

  /// Station `station`'s report of `scan` against this (predicted) picture: its assignment,
  /// each pair's contribution, its unassociated detections.
  Report report(const KnownStation<Sensor>& station, const Scan<Sensor::kMeasDim>& scan,
                AssignmentWork& work) const {
    Report report;
    report.station_id = station.id;
    const ScanAssignment assignment =
        assign_scan(this->estimates(), station.sensor, scan, this->gate(),
                    this->config().association.max_detections_per_scan, work);
    report.dropped = assignment.dropped;
    for (std::size_t t = 0; t < this->tracks().size(); ++t) {
      const int j = assignment.detection_of_track[t];
      if (j < 0) continue;
      add_update(report, station, this->tracks()[t], static_cast<std::uint32_t>(j),
                 scan.detections[static_cast<std::size_t>(j)]);
    }
    for (const std::uint32_t j : assignment.unassociated) {
      report.unassociated.push_back({j, scan.detections[j]});
    }
    return report;
  }

  /// Station `station`'s report rebuilt from what it published (transport/picture_wire.hpp):
  /// its detections, its associations (ascending track id) and its unassociated detections'
  /// indices, each association's contribution computed here against this (predicted) picture's
  /// track — the station's own arithmetic on the same inputs, so its bits when this picture is
  /// the station's. Nothing when an association names a track this picture does not hold:
  /// this picture is not the station's. Every index is within `detections` (the receiver
  /// checked it: picture_scan_from_wire).
  std::optional<Report> report_of(const KnownStation<Sensor>& station,
                                  std::span<const Vector<Sensor::kMeasDim>> detections,
                                  std::span<const std::pair<TrackId, std::uint32_t>> associations,
                                  std::span<const std::uint32_t> unassociated,
                                  std::size_t dropped) const {
    Report report;
    report.station_id = station.id;
    report.dropped = dropped;
    const auto tracks = this->tracks();
    auto next = tracks.begin();  // associations ascend, as tracks do
    for (const auto& [id, j] : associations) {
      next = std::lower_bound(next, tracks.end(), id,
                              [](const auto& track, TrackId wanted) { return track.id < wanted; });
      if (next == tracks.end() || next->id != id) return std::nullopt;
      add_update(report, station, *next, j, detections[j]);
    }
    for (const std::uint32_t j : unassociated) report.unassociated.push_back({j, detections[j]});
    return report;
  }

  /// Fuses the round's reports (one per station that reported, ascending station id) and
  /// closes the round. A track whose fusion fails numerically is left as predicted and counts
  /// as a miss.
  RoundOutcome fuse(std::uint64_t step, std::span<const Report> reports) {
    const std::size_t count = this->tracks().size();
    hit_.assign(count, 0);
    cursor_.assign(reports.size(), 0);
    report_weights_.clear();
    for (const Report& report : reports) report_weights_.push_back(weight_of(report.station_id));
    for (std::size_t t = 0; t < count; ++t) {
      auto& track = this->track(t);
      contributions_.clear();
      weights_.clear();
      track.updated_by.clear();
      for (std::size_t r = 0; r < reports.size(); ++r) {
        const auto& updates = reports[r].updates;
        std::size_t& at = cursor_[r];
        while (at < updates.size() && updates[at].track < track.id) ++at;
        if (at < updates.size() && updates[at].track == track.id) {
          contributions_.push_back(&updates[at].contribution);
          weights_.push_back(report_weights_[r]);
          track.updated_by.push_back(reports[r].station_id);
        }
      }
      if (contributions_.empty()) continue;
      if (Tracks::fuse(track.filter, contributions_, weights_) == NumericalStatus::kOk) {
        hit_[t] = 1;
      } else {
        track.updated_by.clear();
      }
    }
    return this->close_round(step, hit_, [&](std::size_t s) {
      const int id = this->stations()[s].id;
      for (const Report& report : reports) {
        if (report.station_id == id) return std::span(report.unassociated);
      }
      return std::span<const UnassociatedDetection<Sensor::kMeasDim>>();
    });
  }

 private:
  // Adds `track`'s contribution from `station`'s detection `j` of value `z` to `report`; nothing
  // for a pair whose contribution fails numerically (the station publishes none for it, so a
  // peer rebuilding the report skips it too).
  static void add_update(Report& report, const KnownStation<Sensor>& station,
                         const typename Table::TrackType& track, std::uint32_t j,
                         const Vector<Sensor::kMeasDim>& z) {
    typename Report::Update update;
    update.track = track.id;
    update.detection = j;
    const StationObservation<Sensor> observation{station.id, station.sensor, z, station.noise};
    if (Tracks::contribute(track.filter, observation, update.contribution) ==
        NumericalStatus::kOk) {
      report.updates.push_back(std::move(update));
    }
  }

  double weight_of(int station_id) const {
    for (const auto& station : this->stations()) {
      if (station.id == station_id) return station.weight;
    }
    return 1.0;
  }

  std::vector<char> hit_;
  std::vector<std::size_t> cursor_;
  std::vector<double> report_weights_;  // reports[r]'s station's weight
  std::vector<const Contribution*> contributions_;
  std::vector<double> weights_;
};

}  // namespace skyfuse
