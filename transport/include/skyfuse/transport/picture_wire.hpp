#pragma once
/// \file
/// A station's round of the picture on the wire (wire::PictureScan,
/// idl/skyfuse_picture.idl) and back: its scan, its associations against the common predicted
/// picture and its unassociated detections. Values are copied bit for bit, so a peer that
/// computes an association's increment from a received detection computes the station's own.
///
/// A receiver takes a sample only whole: one problem anywhere refuses it, named by the first
/// found, so that a peer never fuses part of a station's round.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "skyfuse/picture/peer_picture.hpp"
#include "skyfuse/picture/picture_sensor.hpp"
#include "skyfuse/picture/scan.hpp"
#include "skyfuse/picture/track_filters.hpp"
#include "skyfuse/transport/wire_conversion.hpp"
#include "skyfuse/validation/drop_kind.hpp"
#include "skyfuse/validation/sample_checks.hpp"
#include "skyfuse/wire/skyfuse_picture.h"

namespace skyfuse::transport {

/// The sample of station `report.station_id`'s round `step`, whose sensor is `sensor`: `scan`'s
/// values, the report's associations (ascending track id, as the report keeps them) and
/// unassociated detections. `picture_digest`: the digest of the predicted picture the report
/// was made against.
template <int N, typename Contribution>
wire::PictureScan to_wire(const PictureSensor<N>& sensor, const Scan& scan,
                          const StationReport<Contribution>& report, std::uint64_t run_id,
                          std::uint32_t step, std::uint64_t picture_digest) {
  const int m = measurement_dim<N>(sensor);
  wire::PictureScan sample;
  sample.run_id(run_id);
  sample.step(step);
  sample.station_id(report.station_id);
  sample.sensor(std::visit([](const auto& s) { return std::string(s.kKind); }, sensor));
  sample.measurement_dim(static_cast<std::uint32_t>(m));
  std::vector<double>& values = sample.values();
  values.reserve(scan.detections.size() * static_cast<std::size_t>(m));
  for (const Detection& z : scan.detections) values.insert(values.end(), z.data(), z.data() + m);
  std::vector<wire::Association>& associations = sample.associations();
  associations.reserve(report.pairs.size());
  for (const ReportedPair& pair : report.pairs) {
    wire::Association association;
    association.track_id(pair.track);
    association.detection(pair.detection);
    association.weight(pair.weight);
    associations.push_back(association);
  }
  std::vector<std::uint32_t>& unassociated = sample.unassociated();
  unassociated.reserve(report.unassociated.size());
  for (const auto& d : report.unassociated) unassociated.push_back(d.detection);
  sample.dropped(static_cast<std::uint32_t>(report.dropped));
  sample.picture_digest(picture_digest);
  sample.addresses(scan.addresses);
  sample.refused_addresses(static_cast<std::uint32_t>(report.refused_addresses));
  sample.identifications(scan.identifications);
  std::vector<double>& reported = sample.reported_std();
  reported.reserve(scan.reported_std.size() * static_cast<std::size_t>(m));
  for (const Detection& s : scan.reported_std)
    reported.insert(reported.end(), s.data(), s.data() + m);
  return sample;
}

/// What a PictureScan carries.
struct ReceivedScan {
  int station_id = 0;
  std::uint32_t step = 0;
  std::uint64_t picture_digest = 0;
  std::vector<Detection> detections;        ///< in scan order, each of its sensor's size
  std::vector<ReportedPair> associations;   ///< ascending (track, detection index)
  std::vector<std::uint32_t> unassociated;  ///< ascending detection index
  std::uint32_t dropped = 0;
  std::vector<Address> addresses;  ///< per detection, in scan order; empty: none has one
  std::uint32_t refused_addresses = 0;
  /// per detection, in scan order; empty: none has one
  std::vector<Identification> identifications;
  /// each detection's stated σ per value (Scan::reported_std), in scan order; empty: none
  std::vector<Detection> reported_std;
  /// The same scan, bit for bit.
  bool operator==(const ReceivedScan& other) const {
    return station_id == other.station_id && step == other.step &&
           picture_digest == other.picture_digest && dropped == other.dropped &&
           addresses == other.addresses && refused_addresses == other.refused_addresses &&
           identifications == other.identifications && associations == other.associations &&
           unassociated == other.unassociated &&
           std::equal(detections.begin(), detections.end(), other.detections.begin(),
                      other.detections.end(), same_detection) &&
           std::equal(reported_std.begin(), reported_std.end(), other.reported_std.begin(),
                      other.reported_std.end(), same_detection);
  }
};

/// `received` as the scan of station `station_id`, of noise `noise`, into `out` (its storage kept
/// from round to round); a scan of no detections where `received` is null (it did not arrive).
inline void assign_scan(Scan& out, int station_id, const DetectionNoise& noise,
                        const ReceivedScan* received) {
  out.station_id = station_id;
  out.noise = noise;
  if (received == nullptr) {
    out.detections.clear();
    out.addresses.clear();
    out.identifications.clear();
    out.reported_std.clear();
    return;
  }
  out.detections = received->detections;
  out.addresses = received->addresses;
  out.identifications = received->identifications;
  out.reported_std = received->reported_std;
}

/// What `scan` published of its detections, as a peer rebuilds its report from them
/// (PeerPicture::report_of).
inline PublishedDetections published(const ReceivedScan& scan) {
  return {scan.detections, scan.addresses, scan.reported_std};
}

/// The sensor kind of each station of a run, by id, as a receiver checks its samples against.
class StationSensorKinds {
 public:
  StationSensorKinds() = default;
  template <int N>
  explicit StationSensorKinds(std::span<const KnownStation<N>> stations) {
    for (const KnownStation<N>& station : stations) {
      kinds_.emplace_back(station.id, std::visit([](const auto& s) { return std::string(s.kKind); },
                                                 station.sensor));
    }
  }
  /// Station `station_id`'s kind; for a station not of the run, the kind its sample claims
  /// (`claimed`), so that what a sample is is checked before who it claims to be.
  std::string_view of(int station_id, std::string_view claimed) const {
    for (const auto& [id, kind] : kinds_) {
      if (id == station_id) return kind;
    }
    return claimed;
  }

 private:
  std::vector<std::pair<int, std::string>> kinds_;
};

namespace detail {
// The detections of `sample` for a station of `Sensor`, appended to `out`, or why not.
template <typename Sensor>
std::optional<DropKind> detections_from_wire(const wire::PictureScan& sample,
                                             std::size_t max_detections,
                                             std::vector<Detection>& out) {
  constexpr int M = Sensor::kMeasDim;
  if (std::string_view(sample.sensor().c_str()) != Sensor::kKind ||
      sample.measurement_dim() != static_cast<std::uint32_t>(M) ||
      sample.values().size() % M != 0) {
    return DropKind::kOutOfRange;
  }
  const std::size_t count = sample.values().size() / M;
  if (count > max_detections) return DropKind::kOutOfRange;
  out.reserve(count);
  for (std::size_t j = 0; j < count; ++j) {
    const Vector<M> z = Eigen::Map<const Vector<M>>(sample.values().data() + j * M);
    if (const auto why = Sensor::check_reported(z)) return why;  // kNonFinite too
    out.emplace_back(z);
  }
  return std::nullopt;
}
// Each detection's stated σ (Scan::reported_std) of `sample`, whose `count` detections hold
// measurement_dim values each, into `out`, or why not: neither none nor one per detection, or a
// σ that is negative (kOutOfRange) or not finite (kNonFinite).
inline std::optional<DropKind> reported_std_from_wire(const wire::PictureScan& sample,
                                                      std::size_t count,
                                                      std::vector<Detection>& out) {
  const std::vector<double>& values = sample.reported_std();
  if (values.empty()) return std::nullopt;
  const std::size_t m = sample.measurement_dim();
  if (values.size() != count * m) return DropKind::kOutOfRange;
  for (const double s : values) {
    if (!std::isfinite(s)) return DropKind::kNonFinite;
    if (s < 0.0) return DropKind::kOutOfRange;
  }
  out.reserve(count);
  for (std::size_t j = 0; j < count; ++j) {
    out.emplace_back(
        Eigen::Map<const Detection>(values.data() + j * m, static_cast<Eigen::Index>(m)));
  }
  return std::nullopt;
}
}  // namespace detail

/// The scan a sample carries for a station whose sensor is of kind `sensor_kind` (one a picture
/// takes, picture/picture_sensor.hpp) with at most `max_detections` detections, or why it is
/// refused:
///  - kOutOfRange: another sensor kind or measurement dimension, values not a whole number of
///    detections, more detections than the bound, addresses (or identifications) neither none
///    nor one per detection, stated σ neither none nor one set per detection or negative, an
///    identification that is no callsign (valid_identification), an
///    index beyond the scan, associations not in strictly ascending (track id, detection) (a pair
///    twice), a weight not in (0, 1], a detection whose weights sum past 1, unassociated indices
///    not strictly ascending, a detection both associated and unassociated, or a detection its
///    sensor cannot report;
///  - kNonFinite: a value, a stated σ or a weight that is not finite.
/// Whether each track id is one of the receiver's picture is the receiver's to check.
inline std::pair<std::optional<ReceivedScan>, std::optional<DropKind>> picture_scan_from_wire(
    const wire::PictureScan& sample, std::string_view sensor_kind, std::size_t max_detections) {
  const auto refuse = [](DropKind why) {
    return std::pair<std::optional<ReceivedScan>, std::optional<DropKind>>(std::nullopt, why);
  };
  ReceivedScan received;
  std::optional<DropKind> why = DropKind::kOutOfRange;  // a kind no picture takes
  for_each_alternative<PictureSensor<kKinematicsDim>>(
      [&]<typename Sensor>(std::type_identity<Sensor>) {
        if (Sensor::kKind == sensor_kind) {
          why = detail::detections_from_wire<Sensor>(sample, max_detections, received.detections);
        }
      });
  if (why) return refuse(*why);
  const std::size_t count = received.detections.size();
  received.station_id = sample.station_id();
  received.step = sample.step();
  received.picture_digest = sample.picture_digest();
  received.dropped = sample.dropped();
  if (!sample.addresses().empty() && sample.addresses().size() != count) {
    return refuse(DropKind::kOutOfRange);
  }
  received.addresses = sample.addresses();
  received.refused_addresses = sample.refused_addresses();
  if (!sample.identifications().empty() && sample.identifications().size() != count) {
    return refuse(DropKind::kOutOfRange);
  }
  for (const Identification id : sample.identifications()) {
    if (!valid_identification(id)) return refuse(DropKind::kOutOfRange);
  }
  received.identifications = sample.identifications();
  if (const auto wrong = detail::reported_std_from_wire(sample, count, received.reported_std)) {
    return refuse(*wrong);
  }
  // Each detection's weights over the tracks it went to sum to at most 1 (a probability; 1 for
  // GNN's one track), and an unassociated detection went to none.
  constexpr double kRoundingOfASum = 1e-9;
  std::vector<double> taken(count, 0.0);
  received.associations.reserve(sample.associations().size());
  for (const wire::Association& a : sample.associations()) {
    const bool ascending =
        received.associations.empty() ||
        std::pair(a.track_id(), a.detection()) >
            std::pair(received.associations.back().track, received.associations.back().detection);
    if (!ascending || a.detection() >= count) return refuse(DropKind::kOutOfRange);
    if (!std::isfinite(a.weight())) return refuse(DropKind::kNonFinite);
    double& sum = taken[a.detection()];
    sum += a.weight();
    if (!(a.weight() > 0.0) || sum > 1.0 + kRoundingOfASum) return refuse(DropKind::kOutOfRange);
    received.associations.push_back({a.track_id(), a.detection(), a.weight()});
  }
  received.unassociated.reserve(sample.unassociated().size());
  for (const std::uint32_t j : sample.unassociated()) {
    const bool ascending = received.unassociated.empty() || j > received.unassociated.back();
    if (!ascending || j >= count || taken[j] != 0.0) return refuse(DropKind::kOutOfRange);
    received.unassociated.push_back(j);
  }
  return {std::move(received), std::nullopt};
}

/// The scan a sample carries for a station of a run whose stations' kinds are `kinds`.
inline std::pair<std::optional<ReceivedScan>, std::optional<DropKind>> picture_scan_from_wire(
    const wire::PictureScan& sample, const StationSensorKinds& kinds, std::size_t max_detections) {
  return picture_scan_from_wire(
      sample, kinds.of(sample.station_id(), std::string_view(sample.sensor().c_str())),
      max_detections);
}

/// Node `source_id`'s picture after round `step`: every track (id, status, estimate), the
/// picture's digest, how many stations' scans the round fused and, where the tracker
/// registers, each registered station's bias estimate. `Table` is a TrackTable, a
/// peer's or the center's.
template <typename Table>
wire::PictureRound picture_round_to_wire(const Table& table, std::uint64_t run_id,
                                         std::uint32_t step, int source_id,
                                         std::uint32_t scans_fused) {
  constexpr int N = Table::kDim;
  wire::PictureRound sample;
  sample.run_id(run_id);
  sample.step(step);
  sample.source_id(source_id);
  sample.picture_digest(table.digest());
  sample.scans_fused(scans_fused);
  const auto tracks = table.tracks();
  std::vector<wire::PictureTrack>& out = sample.tracks();
  out.reserve(tracks.size());
  for (std::size_t t = 0; t < tracks.size(); ++t) {
    const auto& estimate = table.estimates()[t];
    wire::PictureTrack track;
    track.track_id(tracks[t].id);
    track.confirmed(tracks[t].status == TrackStatus::kConfirmed);
    track.x(pack_vector<N>(estimate.mean));
    track.covariance(pack_upper<N>(estimate.covariance));
    track.address(tracks[t].address);
    out.push_back(std::move(track));
  }
  for (const auto& station : table.stations()) {
    if (!table.registers(station.id)) continue;
    const auto& registration = table.bias_of(station.id);
    const SensorBias& b = registration.bias();
    const SensorBias s = registration.sigma();
    wire::PictureBias bias;
    bias.station_id(station.id);
    bias.estimate({b.range_m, b.azimuth_rad, b.elevation_rad, b.time_s});
    bias.sigma({s.range_m, s.azimuth_rad, s.elevation_rad, s.time_s});
    sample.biases().push_back(std::move(bias));
  }
  return sample;
}

namespace detail {

// An IMM track's filter from its modes on the wire: started as `filters` starts any track, then
// given the sent mode states and probabilities; nothing if their number, dimensions or values
// are wrong.
template <typename Tracks>
std::optional<typename Tracks::State> imm_state_from_wire(const wire::PictureStateTrack& t,
                                                          const Tracks& filters) {
  using State = typename Tracks::State;
  constexpr int kModes = State::kModes;
  if (t.modes().size() != static_cast<std::size_t>(kModes) ||
      t.mode_probabilities().size() != static_cast<std::size_t>(kModes)) {
    return std::nullopt;
  }
  const Vector<kModes> probabilities =
      Eigen::Map<const Vector<kModes>>(t.mode_probabilities().data());
  if (check_mode_probabilities(probabilities)) return std::nullopt;
  State state = filters.start(GaussianState<Tracks::kDim>{Vector<Tracks::kDim>::Zero(),
                                                          Covariance<Tracks::kDim>::Identity()});
  typename State::Filter::ModeStates modes;
  bool whole = true;
  State::for_each_mode([&]<int I>(std::integral_constant<int, I>) {
    auto& mode = std::get<I>(modes);
    constexpr int D = std::decay_t<decltype(mode.mean)>::RowsAtCompileTime;
    const auto mean = unpack_vector<D>(t.modes()[I].x());
    const auto covariance = unpack_upper<D>(t.modes()[I].covariance());
    if (!mean || !covariance || !mean->allFinite() || !covariance->allFinite()) {
      whole = false;
      return;
    }
    mode.mean = *mean;
    mode.covariance = *covariance;
  });
  if (!whole) return std::nullopt;
  state.restore(modes, probabilities);
  return state;
}

// A track's cross-covariances with its stations' bias errors (state_dim rows each), or nothing
// if any is wrong: station ids not strictly ascending, a size that is not state_dim times one
// to four biases, a value that is not finite.
inline std::optional<ConsideredBiases> considered_from_wire(const wire::PictureStateTrack& t,
                                                            int state_dim) {
  ConsideredBiases considered;
  for (const wire::PictureConsideredBias& b : t.considered()) {
    if (!considered.empty() && b.station_id() <= considered.back().station_id) return std::nullopt;
    const auto size = static_cast<int>(b.cross().size());
    const int biases = size / state_dim;
    if (biases < 1 || biases > kMaxConsideredBias || size != biases * state_dim ||
        state_dim > kMaxConsideredState) {
      return std::nullopt;
    }
    ConsideredCross cross(state_dim, biases);
    for (int r = 0; r < state_dim; ++r) {
      for (int c = 0; c < biases; ++c)
        cross(r, c) = b.cross()[static_cast<std::size_t>(r * biases + c)];
    }
    if (!cross.allFinite()) return std::nullopt;
    considered.push_back({b.station_id(), std::move(cross)});
  }
  return considered;
}

}  // namespace detail

/// Station `station_id`'s whole picture after round `step`, for a peer that must take it: every
/// track's id, status, history, filter state and last updaters. `Table` is a TrackTable: a
/// single-model track's filter is its Gaussian (x, covariance), an IMM track's its mode
/// probabilities and every mode's state.
template <typename Table>
wire::PictureState picture_state_to_wire(const Table& table, std::uint64_t run_id,
                                         std::uint32_t step, int station_id) {
  constexpr int N = Table::kDim;
  wire::PictureState sample;
  sample.run_id(run_id);
  sample.step(step);
  sample.station_id(station_id);
  sample.picture_digest(table.digest());
  std::vector<wire::PictureStateTrack>& out = sample.tracks();
  out.reserve(table.tracks().size());
  for (const auto& track : table.tracks()) {
    const auto words = track.history.words();
    wire::PictureStateTrack t;
    t.track_id(track.id);
    t.confirmed(track.status == TrackStatus::kConfirmed);
    t.history_hits(words.hits);
    t.history_rounds(words.rounds);
    t.history_misses(words.consecutive_misses);
    using State = std::decay_t<decltype(track.filter)>;
    if constexpr (ImmTrackState<State>) {
      const auto& imm = track.filter.filter();
      const auto& p = imm.mode_probabilities();
      t.mode_probabilities(std::vector<double>(p.data(), p.data() + p.size()));
      State::for_each_mode([&]<int I>(std::integral_constant<int, I>) {
        const auto& mode = imm.template mode_state<I>();
        constexpr int D = std::decay_t<decltype(mode.mean)>::RowsAtCompileTime;
        wire::PictureModeState m;
        m.x(pack_vector<D>(mode.mean));
        m.covariance(pack_upper<D>(mode.covariance));
        t.modes().push_back(std::move(m));
      });
    } else {
      t.x(pack_vector<N>(track.filter.mean));
      t.covariance(pack_upper<N>(track.filter.covariance));
    }
    t.updated_by(track.updated_by);
    t.address(track.address);
    for (const ConsideredBias& c : track.considered) {
      wire::PictureConsideredBias b;
      b.station_id(c.station_id);
      for (Eigen::Index r = 0; r < c.cross.rows(); ++r) {
        for (Eigen::Index k = 0; k < c.cross.cols(); ++k) b.cross().push_back(c.cross(r, k));
      }
      t.considered().push_back(std::move(b));
    }
    out.push_back(std::move(t));
  }
  for (const BiasSums& sums : table.bias_sums()) {
    wire::PictureStateBias b;
    b.station_id(sums.station_id);
    b.information(pack_upper<Eigen::Dynamic>(Eigen::MatrixXd(sums.information)));
    const auto& v = sums.information_vector;
    b.information_vector(std::vector<double>(v.data(), v.data() + v.size()));
    b.detections(sums.detections);
    sample.biases().push_back(std::move(b));
  }
  return sample;
}

/// The registration sums of a PictureState (ascending station id; none where the tracker
/// registers nothing), or nothing if any is wrong: more than the four entries a bias has, an
/// information of another size than its vector, a value that is not finite, station ids not
/// strictly ascending. Whether they are the receiving table's stations' is its to say
/// (TrackTable::restore_biases).
inline std::optional<std::vector<BiasSums>> picture_biases_from_wire(
    const wire::PictureState& sample) {
  std::vector<BiasSums> biases;
  for (const wire::PictureStateBias& b : sample.biases()) {
    if (!biases.empty() && b.station_id() <= biases.back().station_id) return std::nullopt;
    const auto d = static_cast<int>(b.information_vector().size());
    if (d < 1 || d > 4) return std::nullopt;
    const auto information = unpack_upper<Eigen::Dynamic>(b.information(), d);
    const auto vector = unpack_vector<Eigen::Dynamic>(b.information_vector(), d);
    if (!information || !vector || !information->allFinite() || !vector->allFinite()) {
      return std::nullopt;
    }
    biases.push_back({b.station_id(), *information, *vector, b.detections()});
  }
  return biases;
}

/// The tracks of a PictureState for a table of `filters`' tracks (a single model's Gaussian of
/// Tracks::kDim entries, or an IMM's modes), or nothing if anything in it is wrong: a dimension,
/// a number of modes, a value that is not finite, mode probabilities that are not, track ids
/// not strictly ascending, a history no track has, an address held by two tracks.
template <typename Tracks>
std::optional<std::vector<Track<typename Tracks::State>>> picture_state_from_wire(
    const wire::PictureState& sample, const Tracks& filters) {
  using State = typename Tracks::State;
  constexpr int N = Tracks::kDim;
  std::vector<Track<State>> tracks;
  tracks.reserve(sample.tracks().size());
  for (const wire::PictureStateTrack& t : sample.tracks()) {
    if (!tracks.empty() && t.track_id() <= tracks.back().id) return std::nullopt;
    const auto history =
        TrackHistory::from_words({t.history_hits(), t.history_rounds(), t.history_misses()});
    if (!history) return std::nullopt;
    std::optional<State> filter;
    if constexpr (ImmTrackState<State>) {
      if (!t.x().empty() || !t.covariance().empty()) return std::nullopt;
      filter = detail::imm_state_from_wire(t, filters);
    } else {
      if (!t.modes().empty() || !t.mode_probabilities().empty()) return std::nullopt;
      const auto mean = unpack_vector<N>(t.x());
      const auto covariance = unpack_upper<N>(t.covariance());
      if (mean && covariance && mean->allFinite() && covariance->allFinite()) {
        filter = State{*mean, *covariance};
      }
    }
    if (!filter) return std::nullopt;
    Track<State> track{t.track_id(),
                       t.confirmed() ? TrackStatus::kConfirmed : TrackStatus::kTentative,
                       *history,
                       std::move(*filter),
                       {t.updated_by().begin(), t.updated_by().end()}};
    track.address = t.address();
    const auto considered = detail::considered_from_wire(t, N);
    if (!considered) return std::nullopt;
    track.considered = std::move(*considered);
    tracks.push_back(std::move(track));
  }
  std::vector<Address> held;
  for (const auto& track : tracks) {
    if (track.address != kNoAddress) held.push_back(track.address);
  }
  std::sort(held.begin(), held.end());
  if (std::adjacent_find(held.begin(), held.end()) != held.end()) return std::nullopt;
  return tracks;
}

}  // namespace skyfuse::transport
