#pragma once
/// \file
/// The table of tracks every node keeps, peer or center, and what every node does with it the
/// same way: predict every track, and close a round — record which tracks were hit, confirm
/// and delete by the management rule, start tracks from the round's unassociated detections
/// by the initiation rule. How a hit track is updated (peers: summed increments; the center:
/// one stacked update) is the caller's, between the two.
///
/// Tracks are kept in ascending id; a new track's id holds its round in the high bits, so new
/// tracks go at the end and the order never needs sorting.

#include <algorithm>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "skyfuse/filters/kalman.hpp"
#include "skyfuse/metrics/chi_square.hpp"
#include "skyfuse/multitarget/initiation.hpp"
#include "skyfuse/multitarget/scan_assignment.hpp"
#include "skyfuse/multitarget/track.hpp"
#include "skyfuse/multitarget/track_management.hpp"
#include "skyfuse/multitarget/tracker_config.hpp"
#include "skyfuse/scenario/truth.hpp"

namespace skyfuse {

/// A station as every node knows it: its id, its sensor (of the tracks' state), the noise of
/// its detections and its fusion weight. Ascending id in every list.
template <typename Sensor>
struct KnownStation {
  int id = 0;
  Sensor sensor;
  Covariance<Sensor::kMeasDim> noise;
  double weight = 1.0;
};

/// What closing a round did to the table.
struct RoundOutcome {
  std::size_t hit = 0;
  std::size_t confirmed = 0;  ///< tentative tracks confirmed this round
  std::size_t deleted = 0;
  std::size_t started = 0;
};

/// One station's unassociated detection, as it publishes it: index in its scan and value.
template <int M>
struct UnassociatedDetection {
  std::uint32_t detection = 0;
  Vector<M> z;
};

template <typename Model, typename Sensor>
class TrackTable {
 public:
  static constexpr int kDim = Model::kDim;
  static constexpr int kMeasDim = Sensor::kMeasDim;

  /// `initial_variance`: the diagonal of a new track's covariance outside its position and
  /// velocity (the scenario's P0 for the model's other entries).
  TrackTable(const Model& motion, std::vector<KnownStation<Sensor>> stations,
             const TrackerConfig& config, const Vector<kDim>& initial_variance)
      : motion_(motion),
        stations_(std::move(stations)),
        config_(config),
        initial_variance_(initial_variance),
        gate_(chi_square_quantile(config.association.gate_probability, kMeasDim)) {}

  std::span<const Track<kDim>> tracks() const { return tracks_; }
  const std::vector<KnownStation<Sensor>>& stations() const { return stations_; }
  const TrackerConfig& config() const { return config_; }
  /// The chi-square(M) gate of a pair.
  double gate() const { return gate_; }

  /// A track known before the run (the one aircraft of a single-target scenario), confirmed.
  void add_known_track(TrackId id, const GaussianState<kDim>& estimate) {
    Track<kDim> track;
    track.id = id;
    track.status = TrackStatus::kConfirmed;
    track.estimate = estimate;
    tracks_.push_back(std::move(track));
  }

  void predict() {
    for (Track<kDim>& track : tracks_) skyfuse::predict(track.estimate, motion_);
  }

  /// Track i, for the caller's update between predict() and close_round().
  Track<kDim>& track(std::size_t i) { return tracks_[i]; }

  /// Manages every track (hit[i]: whether track i was updated this round), then starts tracks
  /// from `unassociated` (per station, ascending station id as stations(); each ascending).
  template <typename UnassociatedOf>
  RoundOutcome close_round(std::uint64_t step, const std::vector<char>& hit,
                           UnassociatedOf unassociated_of) {
    RoundOutcome outcome;
    std::size_t kept = 0;
    for (std::size_t i = 0; i < tracks_.size(); ++i) {
      if (hit[i]) ++outcome.hit;
      const TrackFate fate = manage_track(tracks_[i], hit[i] != 0, config_.management);
      if (fate == TrackFate::kDeleted) {
        ++outcome.deleted;
        continue;
      }
      if (fate == TrackFate::kConfirmed) ++outcome.confirmed;
      if (kept != i) tracks_[kept] = std::move(tracks_[i]);
      ++kept;
    }
    tracks_.resize(kept);

    fixes_.clear();
    for (std::size_t s = 0; s < stations_.size(); ++s) {
      const KnownStation<Sensor>& station = stations_[s];
      for (const UnassociatedDetection<kMeasDim>& d : unassociated_of(s)) {
        if (const auto fix =
                fix_position(station.id, d.detection, station.sensor, d.z, station.noise)) {
          fixes_.push_back(*fix);
        }
      }
    }
    for (NewTrack& started : initiate_tracks(fixes_, step, config_.initiation)) {
      tracks_.push_back(new_track(std::move(started)));
      ++outcome.started;
    }
    return outcome;
  }

 private:
  Track<kDim> new_track(NewTrack&& started) const {
    Vector<kKinematicsDim> kinematics = Vector<kKinematicsDim>::Zero();
    kinematics.template head<3>() = started.position;
    Track<kDim> track;
    track.id = started.id;
    track.estimate.mean = Model::from_kinematics(kinematics);
    track.estimate.covariance = initial_variance_.asDiagonal();
    track.estimate.covariance.template topLeftCorner<3, 3>() = started.covariance;
    const double v = config_.initiation.velocity_std_mps;
    track.estimate.covariance.template block<3, 3>(3, 3) = v * v * Covariance<3>::Identity();
    track.history.record(true);
    track.updated_by = std::move(started.stations);
    return track;
  }

  Model motion_;
  std::vector<KnownStation<Sensor>> stations_;
  TrackerConfig config_;
  Vector<kDim> initial_variance_;
  double gate_;
  std::vector<Track<kDim>> tracks_;
  std::vector<PositionFix> fixes_;
};

}  // namespace skyfuse
