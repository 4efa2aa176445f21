#pragma once
/// \file
/// The table of tracks every node keeps, peer or center, and what every node does with it the
/// same way: predict every track, associate a station's scan with the predicted tracks by the
/// tracker's parts (hypothesiser.hpp, then the scenario's associator), and close a round — record
/// which tracks were hit, confirm and delete by the management rule, start tracks from the round's
/// unassociated detections by the initiation rule. How a hit track is updated (peers: summed
/// contributions; the center: one update of its detections) is the caller's, between the two.
/// `Tracks` says what a track's filter is (multitarget/track_filters.hpp).
///
/// Identity (identity.hpp) is the table's too: it routes a station's addressed detections before
/// the gate search, and a round's close gives an unaddressed track the address its detections
/// offered and starts tracks from addressed detections.
///
/// Tracks are kept in ascending id; a new track's id holds its round in the high bits, so new
/// tracks go at the end and the order never needs sorting.

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "skyfuse/metrics/chi_square.hpp"
#include "skyfuse/multitarget/associator.hpp"
#include "skyfuse/multitarget/hypothesiser.hpp"
#include "skyfuse/multitarget/identity.hpp"
#include "skyfuse/multitarget/initiation.hpp"
#include "skyfuse/multitarget/picture_digest.hpp"
#include "skyfuse/multitarget/picture_sensor.hpp"
#include "skyfuse/multitarget/track.hpp"
#include "skyfuse/multitarget/track_management.hpp"
#include "skyfuse/multitarget/tracker_config.hpp"
#include "skyfuse/scenario/truth.hpp"

namespace skyfuse {

/// A station as every node knows it: its id, its sensor (of the tracks' N-entry estimate; a
/// value, multitarget/picture_sensor.hpp), the noise of its detections, its fusion weight and
/// what its associator knows of its detections. Ascending id in every list.
template <int N>
struct KnownStation {
  int id = 0;
  PictureSensor<N> sensor;
  DetectionNoise noise;
  double weight = 1.0;
  DetectionPrior prior;
};

/// What closing a round did to the table.
struct RoundOutcome {
  std::size_t hit = 0;
  std::size_t confirmed = 0;  ///< tentative tracks confirmed this round
  std::size_t deleted = 0;
  std::size_t started = 0;
};

/// One station's unassociated detection, as it publishes it: index in its scan, value, address.
struct UnassociatedDetection {
  std::uint32_t detection = 0;
  Detection z;
  Address address = kNoAddress;
};

template <typename Tracks>
class TrackTable {
 public:
  static constexpr int kDim = Tracks::kDim;
  using State = typename Tracks::State;
  using TrackType = Track<State>;
  using Station = KnownStation<kDim>;

  TrackTable(Tracks filters, std::vector<Station> stations, const TrackerConfig& config)
      : filters_(std::move(filters)),
        stations_(std::move(stations)),
        config_(config),
        associator_(find_associator(config.association.associator)) {
    if (associator_ == nullptr) {
      throw std::invalid_argument("tracker.associator: '" + config.association.associator +
                                  "' is none of " + associator_names());
    }
    for (int m = 1; m <= kMaxDetectionDim; ++m) {
      gates_[static_cast<std::size_t>(m)] =
          chi_square_quantile(config.association.gate_probability, m);
      sanity_gates_[static_cast<std::size_t>(m)] =
          chi_square_quantile(config.identity.sanity_gate_probability, m);
    }
  }

  std::span<const TrackType> tracks() const { return tracks_; }
  /// Each track's estimate (tracks()[i]'s), as of the last predict() or close_round().
  std::span<const GaussianState<kDim>> estimates() const { return estimates_; }
  const std::vector<Station>& stations() const { return stations_; }
  const TrackerConfig& config() const { return config_; }
  const Tracks& filters() const { return filters_; }
  Tracks& filters() { return filters_; }
  /// The chi-square(M) gate of a pair of a sensor of M values a detection.
  double gate(int measurement_dim) const {
    return gates_[static_cast<std::size_t>(measurement_dim)];
  }
  const Associator& associator() const { return *associator_; }

  /// Station `station`'s association of its `scan` with this (predicted) picture: its
  /// addressed detections routed to the tracks of their addresses, then the hypotheses of the
  /// other pairs, decided by the scenario's associator.
  ScanAssociation associate(const Station& station, const Scan& scan, AssociationWork& work) const {
    std::visit(
        [&]<typename Sensor>(const Sensor& sensor) {
          constexpr std::size_t M = Sensor::kMeasDim;
          const std::size_t taken =
              std::min(scan.detections.size(), config_.association.max_detections_per_scan);
          route_addressed(estimates(), book_, sensor, scan, taken, sanity_gates_[M], work.routing);
          const std::span<const Address> held =
              book_.empty() ? std::span<const Address>() : std::span<const Address>(addresses_);
          hypothesise(estimates(), sensor, scan, gates_[M],
                      config_.association.max_detections_per_scan, associator_->reads_densities,
                      work.routing.mask(held, scan.addresses), work.hypothesiser, work.hypotheses);
        },
        station.sensor);
    ScanAssociation decided;
    associator_->associate(work.hypotheses, station.prior, config_.association, work, decided);
    merge_routing(work.routing, decided);
    return decided;
  }

  /// A track known before the run (the one aircraft of a single-target scenario), confirmed.
  void add_known_track(TrackId id, const GaussianState<kDim>& estimate) {
    TrackType track{id, TrackStatus::kConfirmed, {}, filters_.start(estimate), {}};
    tracks_.push_back(std::move(track));
    estimates_.push_back(estimate);
    refresh_addresses();
  }

  void predict() {
    for (TrackType& track : tracks_) filters_.predict(track.filter);
    refresh_estimates();
  }

  /// Replaces the whole picture with `tracks` (ascending id): another peer's, taken when this
  /// one's has parted from it.
  void restore(std::vector<TrackType> tracks) {
    tracks_ = std::move(tracks);
    refresh_estimates();
  }

  /// A digest of the picture as it stands (every track's id, status and estimate, bit for
  /// bit): equal at two nodes that hold the same picture, and different, but for a chance of
  /// 2^-64, where they do not. A station publishes its predicted picture's with its scan.
  std::uint64_t digest() const {
    PictureDigest digest(tracks_.size());
    for (std::size_t i = 0; i < tracks_.size(); ++i) {
      digest.add(tracks_[i].id, tracks_[i].status, estimates_[i].mean, estimates_[i].covariance);
      if (tracks_[i].address != kNoAddress) digest.add_address(tracks_[i].address);
    }
    return digest.value();
  }

  /// Track i, for the caller's update between predict() and close_round().
  TrackType& track(std::size_t i) { return tracks_[i]; }

  /// Gives each unaddressed track the address its hit offered (offered[i], kNoAddress for
  /// none: the first station's of weight above 1/2, identity.hpp), manages every track (hit[i]:
  /// whether track i was updated this round), then starts tracks from `unassociated` (per
  /// station, ascending station id as stations(); each ascending).
  template <typename UnassociatedOf>
  RoundOutcome close_round(std::uint64_t step, const std::vector<char>& hit,
                           std::span<const Address> offered, UnassociatedOf unassociated_of) {
    learn_addresses(offered);
    refresh_estimates();
    RoundOutcome outcome;
    std::size_t kept = 0;
    for (std::size_t i = 0; i < tracks_.size(); ++i) {
      if (hit[i]) ++outcome.hit;
      TrackType& track = tracks_[i];
      const double position_variance =
          estimates_[i].covariance.template topLeftCorner<3, 3>().trace();
      const TrackFate fate = manage_track(track.history, track.status, position_variance,
                                          hit[i] != 0, config_.management);
      if (fate == TrackFate::kDeleted) {
        ++outcome.deleted;
        continue;
      }
      if (fate == TrackFate::kConfirmed) ++outcome.confirmed;
      if (kept != i) {
        tracks_[kept] = std::move(tracks_[i]);
        estimates_[kept] = estimates_[i];
      }
      ++kept;
    }
    tracks_.erase(tracks_.begin() + static_cast<std::ptrdiff_t>(kept), tracks_.end());
    estimates_.resize(kept);
    refresh_addresses();

    fixes_.clear();
    for (std::size_t s = 0; s < stations_.size(); ++s) {
      const Station& station = stations_[s];
      std::visit(
          [&]<typename Sensor>(const Sensor& sensor) {
            constexpr int M = Sensor::kMeasDim;
            const Covariance<M> noise = fixed_noise<M>(station.noise);
            for (const UnassociatedDetection& d : unassociated_of(s)) {
              // A track that took this address this round has the aircraft already.
              if (d.address != kNoAddress && book_.track_of(d.address)) continue;
              if (auto fix = fix_position(station.id, d.detection, sensor, fixed_detection<M>(d.z),
                                          noise)) {
                fix->address = d.address;
                fixes_.push_back(*fix);
              }
            }
          },
          station.sensor);
    }
    for (NewTrack& started : initiate_tracks(fixes_, step, config_.initiation)) {
      start_track(std::move(started));
      ++outcome.started;
    }
    refresh_addresses();
    return outcome;
  }

 private:
  void refresh_estimates() {
    estimates_.resize(tracks_.size());
    for (std::size_t i = 0; i < tracks_.size(); ++i) {
      estimates_[i] = filters_.estimate(tracks_[i].filter);
    }
    refresh_addresses();
  }
  void refresh_addresses() {
    addresses_.resize(tracks_.size());
    for (std::size_t i = 0; i < tracks_.size(); ++i) addresses_[i] = tracks_[i].address;
    book_.rebuild(addresses_);
  }

  // Gives each unaddressed track the address offered to it this round, in picture order, unless
  // a track holds it already (one taken earlier in this loop included).
  void learn_addresses(std::span<const Address> offered) {
    for (std::size_t i = 0; i < offered.size(); ++i) {
      const Address address = offered[i];
      if (address == kNoAddress || tracks_[i].address != kNoAddress) continue;
      if (book_.track_of(address)) continue;
      tracks_[i].address = address;
      addresses_[i] = address;
      book_.insert(address, static_cast<int>(i));
    }
  }

  void start_track(NewTrack&& started) {
    Vector<kKinematicsDim> kinematics = Vector<kKinematicsDim>::Zero();
    kinematics.template head<3>() = started.position;
    GaussianState<kDim> initial;
    initial.mean = Tracks::from_kinematics(kinematics);
    initial.covariance = filters_.initial_variance().asDiagonal();
    initial.covariance.template topLeftCorner<3, 3>() = started.covariance;
    const double v = config_.initiation.velocity_std_mps;
    initial.covariance.template block<3, 3>(3, 3) = v * v * Covariance<3>::Identity();
    if (started.velocity) {  // an aircraft's own report of its velocity (initiation.hpp)
      initial.mean.template segment<3>(3) = *started.velocity;
      initial.covariance.template block<3, 3>(3, 3) = started.velocity_covariance;
    }
    TrackType track{started.id,
                    TrackStatus::kTentative,
                    {},
                    filters_.start(initial),
                    std::move(started.stations)};
    track.history.record(true);
    track.address = started.address;
    tracks_.push_back(std::move(track));
    estimates_.push_back(filters_.estimate(tracks_.back().filter));
  }

  Tracks filters_;
  std::vector<Station> stations_;
  TrackerConfig config_;
  std::array<double, kMaxDetectionDim + 1> gates_{};         // by a sensor's values a detection
  std::array<double, kMaxDetectionDim + 1> sanity_gates_{};  // identity's, likewise
  const Associator* associator_;
  std::vector<TrackType> tracks_;
  std::vector<GaussianState<kDim>> estimates_;
  std::vector<PositionFix> fixes_;
  std::vector<Address> addresses_;  // tracks_[i].address, for the gate search's mask
  AddressBook book_;                // the tracks that hold an address, by address
};

}  // namespace skyfuse
