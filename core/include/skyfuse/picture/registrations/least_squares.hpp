#pragma once
/// \file
/// The `least_squares` registration (picture/registration.hpp): every station's biases
/// estimated by recursive least squares in information form (registration/station_bias.hpp),
/// the rule that teaches them one round's pairs, and the station's detections corrected by the
/// estimate with what it does not know yet considered in R. Every node, peer or center, is
/// given the same pairs in the same order, so every node holds the same bits.
///
/// Which prior a pair learns against is the rule's. Where the stations include a reference — a
/// sensor that reports the aircraft's own state (`kReportsOwnState`: ADS-B, Remote ID) — a
/// station's detection of a confirmed track learns against that track's own report of the same
/// round: an absolute measure of the station's biases, made at the same time, independent from
/// round to round. Without one it learns against the track's prior, and only where another
/// station updated the track last round: relative to the others' biases. A reference station
/// learns nothing and is not corrected. With kind `none` the table holds none (active() false)
/// and every detection is taken as its sensor gives it.

#include <algorithm>
#include <cstddef>
#include <span>
#include <variant>
#include <vector>

#include "skyfuse/picture/known_station.hpp"
#include "skyfuse/picture/registration.hpp"
#include "skyfuse/picture/track.hpp"
#include "skyfuse/picture/tracker_config.hpp"
#include "skyfuse/registration/station_bias.hpp"

namespace skyfuse {

template <int N>
class LeastSquaresRegistration {
 public:
  using Station = KnownStation<N>;

  /// None: nothing estimated, nothing corrected.
  LeastSquaresRegistration() = default;
  /// `stations`' registrations where `config` names an estimating kind, none otherwise.
  LeastSquaresRegistration(const RegistrationConfig& config, std::span<const Station> stations) {
    if (!estimates_biases(config)) return;
    const SensorBias prior{config.range_std_m, config.azimuth_std_rad, config.elevation_std_rad,
                           config.time_std_s};
    for (const Station& station : stations) {
      biases_.emplace_back(station.sensor, prior);
      reference_.push_back(reports_own_state(station.sensor));
      has_reference_ = has_reference_ || reference_.back();
    }
  }

  /// Whether anything is estimated.
  bool active() const { return !biases_.empty(); }
  /// Whether the detections of station index `s` are corrected: it is estimated and is no
  /// reference (an aircraft's own report is taken as it is).
  bool corrects(std::size_t s) const { return active() && !reference_[s]; }
  /// Station index `s`'s estimate; active() must hold.
  const StationBias<N>& of(std::size_t s) const { return biases_[s]; }

  /// Station index `s`'s `raw` scan and the tracks' `estimates` as its gate takes them where
  /// it is corrected: its offsets removed and their uncertainty added to R; the clock's
  /// uncertainty (a late clock sees the aircraft further along its velocity) added to each
  /// track's position spread. The clock's correction itself needs a track's velocity: the
  /// pairs' updates take it (correction()).
  void gate_inputs(std::size_t s, const Station& station, const Scan& raw,
                   std::span<const GaussianState<N>> estimates, Scan& scan,
                   std::vector<GaussianState<N>>& priors) const {
    const StationBias<N>& bias = biases_[s];
    // Only a reference's reports state their own σ (Scan::reported_std), and a reference is
    // not corrected: the offsets' noise is added to the station's R alone.
    scan = raw;
    for (Detection& z : scan.detections) z = bias.offsets_removed(station.sensor, z);
    scan.noise += bias.offsets_noise(station.sensor);
    priors.assign(estimates.begin(), estimates.end());
    for (GaussianState<N>& estimate : priors) {
      const Vector3 v = estimate.mean.template segment<3>(3);
      estimate.covariance.template topLeftCorner<3, 3>() +=
          bias.clock_variance() * v * v.transpose();
    }
  }

  /// Station index `s`'s detection `z` as an initiation fix takes it (no track, so no clock's
  /// correction), and what the fix's noise adds to R: what the offsets' estimate does not know.
  Detection offsets_removed(std::size_t s, const Station& station, const Detection& z) const {
    return biases_[s].offsets_removed(station.sensor, z);
  }
  ConsideredCross offsets_factor(std::size_t s, const Station& station) const {
    return biases_[s].offsets_factor(station.sensor);
  }
  DetectionNoise offsets_noise(std::size_t s, const Station& station) const {
    return biases_[s].offsets_noise(station.sensor);
  }

  /// Teaches the estimates one round's pairs of weight 1 (ascending station, then pair, every
  /// node alike) of `tracks` with their `estimates` (the round's priors) and `stations`.
  template <typename TrackList>
  void learn(std::span<const PairedDetection> pairs, const TrackList& tracks,
             std::span<const GaussianState<N>> estimates, std::span<const Station> stations) {
    if (!active()) return;
    if (has_reference_) {
      reference_of_.assign(tracks.size(), nullptr);
      for (const PairedDetection& pair : pairs) {
        if (reference_[pair.station] && reference_of_[pair.track] == nullptr) {
          reference_of_[pair.track] = &pair;
        }
      }
    }
    for (const PairedDetection& pair : pairs) {
      const auto& track = tracks[pair.track];
      if (reference_[pair.station] || track.status != TrackStatus::kConfirmed) continue;
      const Station& station = stations[pair.station];
      if (!has_reference_) {
        // A track only this station holds where it is would teach it its own estimate back.
        if (std::ranges::all_of(track.updated_by, [&](int id) { return id == station.id; })) {
          continue;
        }
        // A track that keeps its cross-covariance with this station's bias error holds part of
        // that error itself (StationBias::learn).
        const ConsideredCross* absorbed = nullptr;
        if constexpr (requires { track.considered; }) {
          for (const ConsideredBias& c : track.considered) {
            if (c.station_id == station.id) absorbed = &c.cross;
          }
        }
        biases_[pair.station].learn(station.sensor, estimates[pair.track], *pair.z, station.noise,
                                    absorbed);
        continue;
      }
      const PairedDetection* reference = reference_of_[pair.track];
      if (reference == nullptr) continue;
      biases_[pair.station].learn(station.sensor,
                                  reported_state(stations[reference->station], *reference->z,
                                                 reference->reported_std, estimates[pair.track]),
                                  *pair.z, station.noise);
    }
  }

  /// Takes what the round taught into the estimates the next round's corrections use.
  void settle() {
    for (StationBias<N>& bias : biases_) bias.settle();
  }

  /// Every station's sums, ascending station id (empty where nothing is estimated): what
  /// another node needs to hold the same estimates (restore()).
  std::vector<BiasSums> sums(std::span<const Station> stations) const {
    std::vector<BiasSums> sums;
    for (std::size_t s = 0; s < biases_.size(); ++s)
      sums.push_back(biases_[s].sums(stations[s].id));
    return sums;
  }
  /// Takes another node's sums() as its own; false, and nothing changed, unless they are every
  /// station's, in order, of its sensor's size.
  bool restore(std::span<const BiasSums> sums, std::span<const Station> stations) {
    if (sums.size() != biases_.size()) return false;
    for (std::size_t s = 0; s < sums.size(); ++s) {
      if (sums[s].station_id != stations[s].id) return false;
    }
    std::vector<StationBias<N>> restored = biases_;
    for (std::size_t s = 0; s < sums.size(); ++s) {
      if (!restored[s].restore(sums[s])) return false;
    }
    biases_ = std::move(restored);
    return true;
  }

 private:
  static bool reports_own_state(const PictureSensor<N>& sensor) {
    return std::visit(
        []<typename S>(const S&) {
          if constexpr (requires { S::kReportsOwnState; }) {
            return S::kReportsOwnState;
          } else {
            return false;
          }
        },
        sensor);
  }

  // The aircraft where its own report `z` (of reference station `source`, stating its own σ
  // `stated` where not null) puts it: the report's position and velocity with its noise, the
  // track's prior for whatever else the state holds (no sensor with a bias reads it).
  static GaussianState<N> reported_state(const Station& source, const Detection& z,
                                         const Detection* stated, const GaussianState<N>& prior) {
    GaussianState<N> reported = prior;
    std::visit(
        [&]<typename S>(const S&) {
          if constexpr (requires { S::kReportsOwnState; }) {
            constexpr int M = S::kMeasDim;
            static_assert(S::kJacobianCols == M, "a report of the state's first M entries");
            reported.mean.template head<M>() = fixed_detection<M>(z);
            reported.covariance.template topRows<M>().setZero();
            reported.covariance.template leftCols<M>().setZero();
            reported.covariance.template topLeftCorner<M, M>() = reported_noise<M>(
                fixed_noise<M>(source.noise), stated != nullptr ? *stated : Detection());
          }
        },
        source.sensor);
    return reported;
  }

  std::vector<StationBias<N>> biases_;  // per station, when the kind estimates
  std::vector<char> reference_;         // per station, with biases_: an aircraft's own report
  bool has_reference_ = false;
  std::vector<const PairedDetection*> reference_of_;  // per track: its reference this round
};

}  // namespace skyfuse
