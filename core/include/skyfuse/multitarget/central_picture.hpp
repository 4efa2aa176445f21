#pragma once
/// \file
/// The fused picture as the fusion center keeps it, from the raw scans: the same rule as the
/// peers' (peer_picture.hpp) — each station's own assignment against the center's predicted
/// tracks, with the same costs, then one stacked update per track of the detections assigned to
/// it (ascending station id), then the same management and initiation. Its prior agrees with
/// the peers' to rounding only, so a pair at a gate's edge could be decided otherwise: the
/// associations are kept for comparison (multitarget/picture_comparison.hpp).

#include <cstdint>
#include <span>
#include <tuple>
#include <vector>

#include "skyfuse/fusion/increment_fusion.hpp"
#include "skyfuse/fusion/stacked_ekf.hpp"
#include "skyfuse/multitarget/track_table.hpp"
#include "skyfuse/tracking/round_rule.hpp"

namespace skyfuse {

/// How the center updates a track with the detections assigned to it (`observations`, ascending
/// station id, with the stations' fusion weights): the EKF's one stacked update, which is the
/// peers' sum for weights of 1, as the single-target center's. false if it failed (the track is
/// left as it was).
template <int N, typename Sensor>
class StackedUpdate {
 public:
  bool operator()(GaussianState<N>& state, std::span<const StationObservation<Sensor>> observations,
                  std::span<const double> /*weights*/) {
    GaussianState<N> updated = state;
    if (stacked_.update(updated, observations).status != NumericalStatus::kOk) return false;
    state = updated;
    return true;
  }

 private:
  StackedEkf<N, Sensor> stacked_;
};

/// The same for a filter part with an increment rule and no stacked form (the unscented
/// filter): each observation's increment by `Rule` against the center's prior, fused onto it,
/// as the single-target center does (sim/increment_run_stepper.hpp).
template <int N, typename Sensor, typename Rule>
class IncrementUpdate {
 public:
  bool operator()(GaussianState<N>& state, std::span<const StationObservation<Sensor>> observations,
                  std::span<const double> weights) {
    increments_.assign(observations.size(), {});
    const NisGate no_gate;  // the assignment's gate screened every pair
    for (std::size_t i = 0; i < observations.size(); ++i) {
      const OwnContribution own = Rule::contribute(state, observations[i], no_gate, increments_[i]);
      if (own.status != NumericalStatus::kOk) return false;
    }
    return fuse_increments(state, std::span<const InformationIncrement<N>>(increments_), weights,
                           state) == NumericalStatus::kOk;
  }

 private:
  std::vector<InformationIncrement<N>> increments_;
};

/// One pair a station's assignment made: which of its detections went to which track.
struct Association {
  int station_id = 0;
  std::uint32_t detection = 0;
  TrackId track = 0;
  bool operator==(const Association&) const = default;
  auto operator<=>(const Association&) const = default;
};

/// `Update`: how a track takes its detections (StackedUpdate, IncrementUpdate).
template <typename Model, typename Sensor, typename Update>
class CentralPicture : public TrackTable<Model, Sensor> {
  using Table = TrackTable<Model, Sensor>;

 public:
  static constexpr int kDim = Model::kDim;
  static constexpr int kMeasDim = Sensor::kMeasDim;
  using Table::Table;

  /// Updates the predicted picture with every station's scan (scans[s] belongs to
  /// stations()[s]) and closes the round.
  RoundOutcome update(std::uint64_t step, std::span<const Scan<kMeasDim>> scans) {
    const std::size_t count = this->tracks().size();
    associations_.clear();
    observations_.assign(count, {});
    weights_.assign(count, {});
    unassociated_.assign(scans.size(), {});
    for (std::size_t s = 0; s < scans.size(); ++s) {
      const KnownStation<Sensor>& station = this->stations()[s];
      const ScanAssignment assignment =
          assign_scan(this->tracks(), station.sensor, scans[s], this->gate(),
                      this->config().association.max_detections_per_scan, work_);
      for (std::size_t t = 0; t < count; ++t) {
        const int j = assignment.detection_of_track[t];
        if (j < 0) continue;
        const auto detection = static_cast<std::uint32_t>(j);
        associations_.push_back({station.id, detection, this->tracks()[t].id});
        observations_[t].push_back(
            {station.id, station.sensor, scans[s].detections[detection], station.noise});
        weights_[t].push_back(station.weight);
      }
      for (const std::uint32_t j : assignment.unassociated) {
        unassociated_[s].push_back({j, scans[s].detections[j]});
      }
    }
    hit_.assign(count, 0);
    for (std::size_t t = 0; t < count; ++t) {
      Track<kDim>& track = this->track(t);
      track.updated_by.clear();
      if (observations_[t].empty()) continue;
      if (!update_(track.estimate, std::span<const StationObservation<Sensor>>(observations_[t]),
                   weights_[t])) {
        continue;
      }
      hit_[t] = 1;
      for (const auto& o : observations_[t]) track.updated_by.push_back(o.station_id);
    }
    return this->close_round(step, hit_, [&](std::size_t s) {
      return std::span<const UnassociatedDetection<kMeasDim>>(unassociated_[s]);
    });
  }

  /// The last round's associations, by station, then track.
  const std::vector<Association>& associations() const { return associations_; }

 private:
  AssignmentWork work_;
  Update update_;
  std::vector<Association> associations_;
  std::vector<std::vector<StationObservation<Sensor>>> observations_;
  std::vector<std::vector<double>> weights_;
  std::vector<std::vector<UnassociatedDetection<kMeasDim>>> unassociated_;
  std::vector<char> hit_;
};

}  // namespace skyfuse
