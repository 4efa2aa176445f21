#pragma once
/// \file
/// The fused picture as every peer keeps it. A round:
///  1. every peer predicts every track (TrackTable::predict);
///  2. each station assigns its own scan to the predicted tracks and turns each pair into its
///     filter part's increment against the track's prior (station_report): what it publishes,
///     with its unassociated detections;
///  3. every peer fuses each track's increments in ascending station id — a track no station
///     updated is a miss — and closes the round: management, then initiation from every
///     station's unassociated detections (PeerPicture::fuse).
/// Same picture + same reports = same bits at every peer.

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "skyfuse/fusion/increment_fusion.hpp"
#include "skyfuse/fusion/station_observation.hpp"
#include "skyfuse/multitarget/track_table.hpp"
#include "skyfuse/tracking/round_rule.hpp"
#include "skyfuse/validation/nis_gate.hpp"

namespace skyfuse {

/// What a station publishes of a round.
template <int N, int M>
struct StationReport {
  struct Update {
    TrackId track = 0;
    std::uint32_t detection = 0;
    InformationIncrement<N> increment;
  };
  int station_id = 0;
  std::vector<Update> updates;                         ///< ascending track id
  std::vector<UnassociatedDetection<M>> unassociated;  ///< ascending detection index
  std::size_t dropped = 0;  ///< detections beyond the assignment's bound, left out
};

/// Station `station`'s report of `scan` against the predicted `table`: its assignment, each
/// pair's increment by the filter part's rule `Rule`, its unassociated detections.
template <typename Rule, typename Model, typename Sensor>
StationReport<Model::kDim, Sensor::kMeasDim> station_report(const TrackTable<Model, Sensor>& table,
                                                            const KnownStation<Sensor>& station,
                                                            const Scan<Sensor::kMeasDim>& scan,
                                                            AssignmentWork& work) {
  constexpr int N = Model::kDim;
  StationReport<N, Sensor::kMeasDim> report;
  report.station_id = station.id;
  const ScanAssignment assignment =
      assign_scan(table.tracks(), station.sensor, scan, table.gate(),
                  table.config().association.max_detections_per_scan, work);
  report.dropped = assignment.dropped;
  const NisGate no_gate;  // the assignment's gate has screened every pair
  for (std::size_t t = 0; t < table.tracks().size(); ++t) {
    const int j = assignment.detection_of_track[t];
    if (j < 0) continue;
    typename StationReport<N, Sensor::kMeasDim>::Update update;
    update.track = table.tracks()[t].id;
    update.detection = static_cast<std::uint32_t>(j);
    const StationObservation<Sensor> observation{
        station.id, station.sensor, scan.detections[static_cast<std::size_t>(j)], station.noise};
    const OwnContribution own =
        Rule::contribute(table.tracks()[t].estimate, observation, no_gate, update.increment);
    if (own.status != NumericalStatus::kOk || own.refused) continue;  // nothing to add
    report.updates.push_back(std::move(update));
  }
  for (const std::uint32_t j : assignment.unassociated) {
    report.unassociated.push_back({j, scan.detections[j]});
  }
  return report;
}

template <typename Model, typename Sensor>
class PeerPicture : public TrackTable<Model, Sensor> {
  using Table = TrackTable<Model, Sensor>;

 public:
  static constexpr int kDim = Model::kDim;
  using Report = StationReport<kDim, Sensor::kMeasDim>;
  using Table::Table;

  /// Fuses the round's reports (one per station that reported, ascending station id) and
  /// closes the round. A track whose fusion fails numerically is left as predicted and counts
  /// as a miss.
  RoundOutcome fuse(std::uint64_t step, std::span<const Report> reports) {
    const std::size_t count = this->tracks().size();
    hit_.assign(count, 0);
    cursor_.assign(reports.size(), 0);
    for (std::size_t t = 0; t < count; ++t) {
      Track<kDim>& track = this->track(t);
      increments_.clear();
      weights_.clear();
      track.updated_by.clear();
      for (std::size_t r = 0; r < reports.size(); ++r) {
        const auto& updates = reports[r].updates;
        std::size_t& at = cursor_[r];
        while (at < updates.size() && updates[at].track < track.id) ++at;
        if (at < updates.size() && updates[at].track == track.id) {
          increments_.push_back(updates[at].increment);
          weights_.push_back(weight_of(reports[r].station_id));
          track.updated_by.push_back(reports[r].station_id);
        }
      }
      if (increments_.empty()) continue;
      if (fuse_increments(track.estimate, std::span<const InformationIncrement<kDim>>(increments_),
                          weights_, track.estimate) == NumericalStatus::kOk) {
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
  double weight_of(int station_id) const {
    for (const auto& station : this->stations()) {
      if (station.id == station_id) return station.weight;
    }
    return 1.0;
  }

  std::vector<char> hit_;
  std::vector<std::size_t> cursor_;
  std::vector<InformationIncrement<kDim>> increments_;
  std::vector<double> weights_;
};

}  // namespace skyfuse
