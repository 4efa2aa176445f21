#pragma once
/// \file
/// The definitions of TrackTable's rounds (track_table.hpp). Only the files that compile the
/// pictures once per filter part and motion model include it (core/src/picture/
/// pictures_shard.cpp): every other file calls the compiled
/// code, which keeps the per-track arithmetic out of the node processes' and the tests' builds.

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>

#include "skyfuse/picture/picture_digest.hpp"
#include "skyfuse/picture/station_hypotheses.hpp"
#include "skyfuse/picture/track_management.hpp"
#include "skyfuse/picture/track_table.hpp"

namespace skyfuse {

template <typename Tracks>
ScanAssociation TrackTable<Tracks>::associate(const Station& station, const Scan& raw,
                                              AssociationWork& work) const {
  // A registered station's detections are gated as its registration corrects them
  // (LeastSquaresRegistration::gate_inputs).
  Scan offset_free;
  std::vector<GaussianState<kDim>> gated;
  const std::size_t s = station_index(station.id);
  const bool registered = registration_.corrects(s);
  if (registered) registration_.gate_inputs(s, station, raw, estimates(), offset_free, gated);
  const Scan& scan = registered ? offset_free : raw;
  const std::span<const GaussianState<kDim>> priors =
      registered ? std::span<const GaussianState<kDim>>(gated) : estimates();
  const std::span<const Address> held =
      book_.empty() ? std::span<const Address>() : std::span<const Address>(addresses_);
  hypothesise_station_scan(priors, book_, held, station.sensor, scan, gates_, sanity_gates_,
                           config_.association.max_detections_per_scan,
                           associator_->reads_densities, work);
  ScanAssociation decided;
  associator_->associate(work.hypotheses, station.prior, config_.association, work, decided);
  merge_routing(work.routing, decided);
  return decided;
}

template <typename Tracks>
void TrackTable<Tracks>::add_known_track(TrackId id, const GaussianState<kDim>& estimate) {
  TrackType track{id, TrackStatus::kConfirmed, {}, filters_.start(estimate), {}};
  tracks_.push_back(std::move(track));
  estimates_.push_back(estimate);
  refresh_addresses();
}

template <typename Tracks>
void TrackTable<Tracks>::predict() {
  for (TrackType& track : tracks_) {
    if constexpr (ConsidersBiases<Tracks>) {
      filters_.predict_considered(track.filter, track.considered);
    }
    filters_.predict(track.filter);
  }
  refresh_estimates();
}

template <typename Tracks>
void TrackTable<Tracks>::restore(std::vector<TrackType> tracks) {
  tracks_ = std::move(tracks);
  refresh_estimates();
}

template <typename Tracks>
std::uint64_t TrackTable<Tracks>::digest() const {
  PictureDigest digest(tracks_.size());
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    digest.add(tracks_[i].id, tracks_[i].status, estimates_[i].mean, estimates_[i].covariance);
    if (tracks_[i].address != kNoAddress) digest.add_address(tracks_[i].address);
  }
  return digest.value();
}

template <typename Tracks>
void TrackTable<Tracks>::condition_on_settled_biases() {
  // A track whose error is correlated with a station's bias error learns what the settle
  // learnt of it (registration/considered_biases.hpp, settle_considered). The stations' biases
  // are independent, so each station's is taken on its own.
  for (TrackType& track : tracks_) {
    for (ConsideredBias& c : track.considered) {
      const StationBias<kDim>& bias = registration_.of(station_index(c.station_id));
      settle_considered(track.filter, c, bias.last_move(), bias.last_narrowing());
    }
  }
}

template <typename Tracks>
template <typename UnassociatedOf>
RoundOutcome TrackTable<Tracks>::close_round(std::uint64_t step, const std::vector<char>& hit,
                                             std::span<const Address> offered,
                                             UnassociatedOf unassociated_of) {
  // What this round taught each station's registration corrects the next round's detections.
  registration_.settle();
  if constexpr (ConsidersBiases<Tracks>) {
    if (registers()) condition_on_settled_biases();
  }
  learn_addresses(offered);
  // A track's height no less known than the band the 2-D radars assume (height_bound.hpp).
  if (height_band_) {
    for (TrackType& track : tracks_) bound_height(track.filter, *height_band_);
  }
  refresh_estimates();
  RoundOutcome outcome;
  outcome.deleted = erase_tracks_if([&](std::size_t i) {
    if (hit[i]) ++outcome.hit;
    TrackType& track = tracks_[i];
    const double position_variance =
        estimates_[i].covariance.template topLeftCorner<3, 3>().trace();
    const TrackFate fate = manage_track(track.history, track.status, position_variance, hit[i] != 0,
                                        config_.management);
    if (fate == TrackFate::kConfirmed) ++outcome.confirmed;
    return fate == TrackFate::kDeleted;
  });
  // One aircraft, one track (track_merge.hpp); nothing to merge where no track holds an address.
  if (!book_.empty() && find_tracks_held_twice(std::span<const TrackType>(tracks_),
                                               std::span<const GaussianState<kDim>>(estimates_),
                                               merge_gate_, merge_work_) > 0) {
    outcome.merged = erase_tracks_if([&](std::size_t i) { return merge_work_.dropped[i] != 0; });
  }
  refresh_addresses();

  fixes_.clear();
  fix_bias_cross_.clear();
  for (std::size_t s = 0; s < stations_.size(); ++s) {
    const Station& station = stations_[s];
    std::visit(
        [&]<typename Sensor>(const Sensor& sensor) {
          constexpr int M = Sensor::kMeasDim;
          // A registered station's fix carries what its offsets' estimate does not know yet.
          const bool registered = registration_.corrects(s);
          const Covariance<M> station_noise = fixed_noise<M>(station.noise);
          for (const UnassociatedDetection& d : unassociated_of(s)) {
            // A track that took this address this round has the aircraft already.
            if (d.address != kNoAddress && book_.track_of(d.address)) continue;
            const Detection z = registered ? registration_.offsets_removed(s, station, d.z) : d.z;
            Covariance<M> noise = reported_noise<M>(station_noise, d.reported_std);
            if (registered) noise += fixed_noise<M>(registration_.offsets_noise(s, station));
            if (auto fix =
                    fix_position(station.id, d.detection, sensor, fixed_detection<M>(z), noise)) {
              fix->address = d.address;
              fixes_.push_back(*fix);
              if constexpr (ConsidersBiases<Tracks>) {
                fix_bias_cross_.push_back(
                    registered ? fix_bias_cross(sensor, *fix, noise,
                                                registration_.offsets_factor(s, station))
                               : ConsideredCross());
              }
            }
          }
        },
        station.sensor);
  }
  for (NewTrack& started : initiate_tracks(fixes_, step, config_.initiation, join_gate_)) {
    start_track(std::move(started));
    ++outcome.started;
  }
  refresh_addresses();
  return outcome;
}

template <typename Tracks>
template <typename Drop>
std::size_t TrackTable<Tracks>::erase_tracks_if(Drop drop) {
  std::size_t kept = 0;
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    if (drop(i)) continue;
    if (kept != i) {
      tracks_[kept] = std::move(tracks_[i]);
      estimates_[kept] = estimates_[i];
    }
    ++kept;
  }
  const std::size_t erased = tracks_.size() - kept;
  tracks_.erase(tracks_.begin() + static_cast<std::ptrdiff_t>(kept), tracks_.end());
  estimates_.resize(kept);
  return erased;
}

template <typename Tracks>
void TrackTable<Tracks>::refresh_estimates() {
  estimates_.resize(tracks_.size());
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    estimates_[i] = filters_.estimate(tracks_[i].filter);
  }
  refresh_addresses();
}

template <typename Tracks>
void TrackTable<Tracks>::refresh_addresses() {
  addresses_.resize(tracks_.size());
  for (std::size_t i = 0; i < tracks_.size(); ++i) addresses_[i] = tracks_[i].address;
  book_.rebuild(addresses_);
}

template <typename Tracks>
void TrackTable<Tracks>::learn_addresses(std::span<const Address> offered) {
  for (std::size_t i = 0; i < offered.size(); ++i) {
    const Address address = offered[i];
    if (address == kNoAddress || tracks_[i].address != kNoAddress) continue;
    if (book_.track_of(address)) continue;
    tracks_[i].address = address;
    addresses_[i] = address;
    book_.insert(address, static_cast<int>(i));
  }
}

template <typename Tracks>
void TrackTable<Tracks>::start_track(NewTrack&& started) {
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
  if constexpr (ConsidersBiases<Tracks>) {
    // Its position is the information-weighted mean of its fixes, so a registered station's
    // offsets error moves it by P₀ Hᵀ R⁻¹ E L u, and its error x − x̂ by the opposite: its C̃
    // from the start is −P₀ Hᵀ R⁻¹ E L (track_table.hpp).
    for (const std::size_t f : started.fixes) {
      const ConsideredCross& weighed = fix_bias_cross_[f];
      if (weighed.size() == 0) continue;
      ConsideredCross cross = ConsideredCross::Zero(kDim, weighed.cols());
      cross.topRows(3).noalias() = -started.covariance * weighed;
      track.considered.push_back({fixes_[f].station_id, std::move(cross)});
    }
  }
  tracks_.push_back(std::move(track));
  estimates_.push_back(filters_.estimate(tracks_.back().filter));
}

}  // namespace skyfuse
