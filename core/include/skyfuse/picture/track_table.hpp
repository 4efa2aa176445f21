#pragma once
/// \file
/// The table of tracks every node keeps, peer or center, and what every node does with it the
/// same way: predict every track, associate a station's scan with the predicted tracks by the
/// tracker's parts (hypothesiser.hpp, then the scenario's associator), and close a round — record
/// which tracks were hit, confirm and delete by the management rule, start tracks from the round's
/// unassociated detections by the initiation rule. How a hit track is updated (peers: summed
/// contributions; the center: one update of its detections) is the caller's, between the two.
/// `Tracks` says what a track's filter is (picture/track_filters.hpp).
///
/// Identity (identity.hpp) is the table's too: it routes a station's addressed detections before
/// the gate search, and a round's close gives an unaddressed track the address its detections
/// offered and starts tracks from addressed detections.
///
/// Tracks are kept in ascending id; a new track's id holds its round in the high bits, so new
/// tracks go at the end and the order never needs sorting.
///
/// The rounds are defined in track_table_impl.hpp and compiled once per filter part and motion
/// model in skyfuse_core (core/src/picture/pictures_shard.cpp); this header declares them.

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "skyfuse/metrics/chi_square.hpp"
#include "skyfuse/picture/associator.hpp"
#include "skyfuse/picture/height_bound.hpp"
#include "skyfuse/picture/hypothesiser.hpp"
#include "skyfuse/picture/identity.hpp"
#include "skyfuse/picture/initiation.hpp"
#include "skyfuse/picture/known_station.hpp"
#include "skyfuse/picture/picture_digest.hpp"
#include "skyfuse/picture/picture_sensor.hpp"
#include "skyfuse/picture/registrations/least_squares.hpp"
#include "skyfuse/picture/station_hypotheses.hpp"
#include "skyfuse/picture/track.hpp"
#include "skyfuse/picture/track_management.hpp"
#include "skyfuse/picture/track_merge.hpp"
#include "skyfuse/picture/tracker_config.hpp"
#include "skyfuse/scenario/truth.hpp"

namespace skyfuse {

/// What closing a round did to the table.
struct RoundOutcome {
  std::size_t hit = 0;
  std::size_t confirmed = 0;  ///< tentative tracks confirmed this round
  std::size_t deleted = 0;
  std::size_t started = 0;
  /// Tracks without an address dropped as holding the aircraft of a track with one
  /// (track_merge.hpp).
  std::size_t merged = 0;
};

/// One station's unassociated detection, as it publishes it: index in its scan, value, address,
/// and the σ its report states (Scan::reported_std; empty: none).
struct UnassociatedDetection {
  std::uint32_t detection = 0;
  Detection z;
  Address address = kNoAddress;
  Detection reported_std{};
};

/// Hᵀ R⁻¹ W (3 × D) for `fix`, a detection of `sensor` with noise R (the offsets' noise in it)
/// whose error holds W u besides its noise (W = E L, StationBias::offsets_factor): the fix's
/// information times how far u moves it, so that a track started at the information-weighted
/// mean of its fixes, of covariance P₀, holds −P₀ Hᵀ R⁻¹ W as its error's cross-covariance with
/// u (the fix moves with u; the error x − x̂ against it).
template <typename Sensor>
ConsideredCross fix_bias_cross(const Sensor& sensor, const PositionFix& fix,
                               const Covariance<Sensor::kMeasDim>& noise,
                               const ConsideredCross& weighed_offsets) {
  constexpr int M = Sensor::kMeasDim;
  Vector<Sensor::kStateDim> x = Vector<Sensor::kStateDim>::Zero();
  x.template head<3>() = fix.position;
  const Matrix<M, 3> h = sensor.jacobian(x).template leftCols<3>();
  SmallCholesky<M> r_factor;
  if (!r_factor.compute(noise)) return ConsideredCross();  // the fix factored it: not reached
  ConsideredCross cross(3, weighed_offsets.cols());
  for (Eigen::Index c = 0; c < weighed_offsets.cols(); ++c) {
    const Vector<M> r_inv_w = r_factor.solve(Vector<M>(weighed_offsets.col(c)));
    cross.col(c) = h.transpose() * r_inv_w;
  }
  return cross;
}

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
        associator_(find_associator(config.association.associator)),
        registration_(config.registration, stations_),
        height_band_(assumed_height_band(std::span<const Station>(stations_))) {
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
    join_gate_ = join_gate(config.initiation);
    if (config.identity.merge_probability > 0.0) {
      merge_gate_ = chi_square_quantile(config.identity.merge_probability, kMergeDim);
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
  ScanAssociation associate(const Station& station, const Scan& scan, AssociationWork& work) const;

  /// A track known before the run (the one aircraft of a single-target scenario), confirmed.
  void add_known_track(TrackId id, const GaussianState<kDim>& estimate);

  void predict();

  /// Replaces the whole picture with `tracks` (ascending id): another peer's, taken when this
  /// one's has parted from it.
  void restore(std::vector<TrackType> tracks);

  /// A digest of the picture as it stands (every track's id, status and estimate, bit for
  /// bit): equal at two nodes that hold the same picture, and different, but for a chance of
  /// 2^-64, where they do not. A station publishes its predicted picture's with its scan.
  std::uint64_t digest() const;

  /// Track i, for the caller's update between predict() and close_round().
  TrackType& track(std::size_t i) { return tracks_[i]; }

  /// The index in stations() of station `station_id`, which the table knows.
  std::size_t station_index(int station_id) const {
    const auto at = std::lower_bound(stations_.begin(), stations_.end(), station_id,
                                     [](const Station& s, int id) { return s.id < id; });
    return static_cast<std::size_t>(at - stations_.begin());
  }
  /// The registration (registration.hpp), the scenario's kind: what the pictures' updates
  /// correct a station's detections by.
  const LeastSquaresRegistration<kDim>& registration() const { return registration_; }
  /// Whether the scenario registers its stations (TrackerConfig::registration).
  bool registers() const { return registration_.active(); }
  /// Whether station `station_id`'s detections are corrected by the registration.
  bool registers(int station_id) const { return registration_.corrects(station_index(station_id)); }
  /// Station `station_id`'s estimate; registers() must hold.
  const StationBias<kDim>& bias_of(int station_id) const {
    return registration_.of(station_index(station_id));
  }
  /// Every station's registration sums, ascending station id (empty where nothing registers):
  /// what another node needs to hold the same estimates (restore_biases).
  std::vector<BiasSums> bias_sums() const { return registration_.sums(stations_); }
  /// Takes another node's bias_sums() as this table's, with the picture it restore()s; false,
  /// and nothing changed, unless they are every station's, in order, of its sensor's size.
  bool restore_biases(std::span<const BiasSums> sums) {
    return registration_.restore(sums, stations_);
  }
  /// Teaches the registration one round's pairs of weight 1, ascending station then pair, as
  /// every node gives them (LeastSquaresRegistration::learn).
  void learn_biases(std::span<const PairedDetection> pairs) {
    registration_.learn(pairs, tracks_, estimates_, stations_);
  }

 protected:
  /// Gives each unaddressed track the address its hit offered (offered[i], kNoAddress for
  /// none: the first station's of weight above 1/2, identity.hpp), manages every track (hit[i]:
  /// whether track i was updated this round), drops the unaddressed tracks that hold an
  /// addressed track's aircraft (track_merge.hpp), then starts tracks from `unassociated` (per
  /// station, ascending station id as stations(); each ascending). For the pictures' own
  /// rounds (peer_picture.hpp, central_picture.hpp), compiled with them.
  template <typename UnassociatedOf>
  RoundOutcome close_round(std::uint64_t step, const std::vector<char>& hit,
                           std::span<const Address> offered, UnassociatedOf unassociated_of);

 private:
  void refresh_estimates();
  // Each track that keeps cross-covariances with the bias errors, conditioned on what this
  // round's settle learnt of them (track_table_impl.hpp).
  void condition_on_settled_biases();
  void refresh_addresses();
  // Removes the tracks for which drop(i) holds (it may change track i first, as management
  // does), the others kept in order with their estimates; how many it removed.
  template <typename Drop>
  std::size_t erase_tracks_if(Drop drop);
  // Gives each unaddressed track the address offered to it this round, in picture order, unless
  // a track holds it already (one taken earlier in this loop included).
  void learn_addresses(std::span<const Address> offered);
  void start_track(NewTrack&& started);

  Tracks filters_;
  std::vector<Station> stations_;
  TrackerConfig config_;
  GatesByDimension gates_{};         // by a sensor's values a detection
  GatesByDimension sanity_gates_{};  // identity's, likewise
  double join_gate_ = 0.0;           // initiation's (initiation.hpp)
  double merge_gate_ = 0.0;          // track_merge.hpp's; 0: no merge
  MergeWork merge_work_;
  const Associator* associator_;
  std::vector<TrackType> tracks_;
  std::vector<GaussianState<kDim>> estimates_;
  std::vector<PositionFix> fixes_;
  // Beside each fix, a registered station's Hᵀ R⁻¹ E L (3 × D; empty for another's): the
  // offsets' error it carries, u = L⁻¹ (b − b̂) standardised, weighed as the fix is. A track
  // started from it holds −P₀ Hᵀ R⁻¹ E L as its C̃ (registration/considered_biases.hpp).
  std::vector<ConsideredCross> fix_bias_cross_;
  std::vector<Address> addresses_;  // tracks_[i].address, for the gate search's mask
  AddressBook book_;                // the tracks that hold an address, by address
  LeastSquaresRegistration<kDim> registration_;
  std::optional<HeightBand> height_band_;  // the 2-D radars' (height_bound.hpp); none: no bound
};

}  // namespace skyfuse
