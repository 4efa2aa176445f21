#pragma once
/// \file
/// The definitions of PeerPicture's rounds (peer_picture.hpp). Only the file that compiles the
/// peers' pictures once per filter part and motion model includes it (core/src/picture/
/// pictures_shard.cpp): every other file calls the compiled code.

#include <algorithm>
#include <optional>
#include <span>
#include <stdexcept>
#include <utility>
#include <variant>

#include "skyfuse/picture/peer_picture.hpp"
#include "skyfuse/picture/track_table_impl.hpp"

namespace skyfuse {

template <typename Tracks>
auto PeerPicture<Tracks>::report(const Station& station, const Scan& scan,
                                 AssociationWork& work) const -> Report {
  Report report;
  report.station_id = station.id;
  const ScanAssociation association = this->associate(station, scan, work);
  report.dropped = association.dropped;
  report.refused_addresses = association.refused_addresses;
  const auto tracks = this->tracks();
  const std::span<const WeightedPair> pairs(association.pairs);
  report.updates.reserve(pairs.size());
  report.pairs.reserve(pairs.size());
  for (std::size_t first = 0; first < pairs.size();) {
    std::size_t end = first;
    while (end < pairs.size() && pairs[end].track == pairs[first].track) ++end;
    add_update(report, station, tracks[static_cast<std::size_t>(pairs[first].track)],
               pairs.subspan(first, end - first),
               PublishedDetections{scan.detections, scan.addresses, scan.reported_std});
    first = end;
  }
  for (const std::uint32_t j : association.unassociated) {
    report.unassociated.push_back({j, scan.detections[j], address_of(scan.addresses, j),
                                   reported_std_at(scan.reported_std, j)});
  }
  return report;
}

template <typename Tracks>
auto PeerPicture<Tracks>::report_of(const Station& station, const PublishedDetections& detections,
                                    std::span<const ReportedPair> pairs,
                                    std::span<const std::uint32_t> unassociated,
                                    std::size_t dropped) const -> std::optional<Report> {
  Report report;
  report.station_id = station.id;
  report.dropped = dropped;
  const auto tracks = this->tracks();
  auto next = tracks.begin();  // pairs ascend, as tracks do
  for (auto pair = pairs.begin(); pair != pairs.end();) {
    auto end = pair;
    while (end != pairs.end() && end->track == pair->track) ++end;
    next = std::lower_bound(next, tracks.end(), pair->track,
                            [](const auto& track, TrackId wanted) { return track.id < wanted; });
    if (next == tracks.end() || next->id != pair->track) return std::nullopt;
    add_update(report, station, *next, std::span<const ReportedPair>(pair, end), detections);
    pair = end;
  }
  for (const std::uint32_t j : unassociated) {
    report.unassociated.push_back({j, detections.values[j], address_of(detections.addresses, j),
                                   reported_std_at(detections.reported_std, j)});
  }
  return report;
}

template <typename Tracks>
RoundOutcome PeerPicture<Tracks>::fuse(std::uint64_t step, std::span<const Report> reports) {
  const std::size_t count = this->tracks().size();
  hit_.assign(count, 0);
  cursor_.assign(reports.size(), 0);
  report_weights_.clear();
  for (const Report& report : reports) report_weights_.push_back(weight_of(report.station_id));
  offered_.assign(count, kNoAddress);
  // Registration: each station's raw detections of tracks, in ascending station id and pair
  // order — the same sums at every peer.
  if (this->registers()) {
    std::vector<PairedDetection> learned;
    for (const Report& report : reports) {
      const std::size_t station = this->station_index(report.station_id);
      auto next = this->tracks().begin();
      // Each pair has its detection (add_update_of keeps them together where anything registers).
      const std::size_t pairs = std::min(report.pairs.size(), report.paired_detections.size());
      for (std::size_t p = 0; p < pairs; ++p) {
        if (report.pairs[p].weight != 1.0) continue;  // a weighed pair is no certain one
        next =
            std::lower_bound(next, this->tracks().end(), report.pairs[p].track,
                             [](const auto& track, TrackId wanted) { return track.id < wanted; });
        // A report names only this picture's tracks (report_of gives none otherwise).
        if (next == this->tracks().end() || next->id != report.pairs[p].track) break;
        learned.push_back({station, static_cast<std::size_t>(next - this->tracks().begin()),
                           &report.paired_detections[p], &report.paired_reported_std[p]});
      }
    }
    this->learn_biases(learned);
  }
  considered_cursor_.assign(reports.size(), 0);
  // Only a registered station's report carries terms (ConsidersBiases).
  const bool any_terms =
      std::ranges::any_of(reports, [](const Report& report) { return !report.considered.empty(); });
  for (std::size_t t = 0; t < count; ++t) {
    auto& track = this->track(t);
    contributions_.clear();
    weights_.clear();
    terms_.clear();
    term_weights_.clear();
    track.updated_by.clear();
    for (std::size_t r = 0; r < reports.size(); ++r) {
      const auto& updates = reports[r].updates;
      std::size_t& at = cursor_[r];
      while (at < updates.size() && updates[at].track < track.id) ++at;
      if (at < updates.size() && updates[at].track == track.id) {
        contributions_.push_back(&updates[at].contribution);
        weights_.push_back(report_weights_[r]);
        if (offered_[t] == kNoAddress) offered_[t] = updates[at].address;
        track.updated_by.push_back(reports[r].station_id);
      }
      if (!any_terms) continue;
      const auto& considered = reports[r].considered;
      std::size_t& next = considered_cursor_[r];
      while (next < considered.size() && considered[next].track < track.id) ++next;
      if (next < considered.size() && considered[next].track == track.id) {
        terms_.push_back(considered[next].terms);
        term_weights_.push_back(report_weights_[r]);
      }
    }
    if (contributions_.empty()) continue;
    NumericalStatus fused = NumericalStatus::kOk;
    if constexpr (ConsidersBiases<Tracks>) {
      if (!track.considered.empty() || !terms_.empty()) {
        fused = Tracks::fuse_considered(track.filter, track.considered, contributions_, weights_,
                                        terms_, term_weights_);
      } else {
        fused = Tracks::fuse(track.filter, contributions_, weights_);
      }
    } else {
      fused = Tracks::fuse(track.filter, contributions_, weights_);
    }
    if (fused == NumericalStatus::kOk) {
      hit_[t] = 1;
    } else {
      track.updated_by.clear();
      offered_[t] = kNoAddress;  // a miss offers nothing
    }
  }
  return this->close_round(step, hit_, offered_, [&](std::size_t s) {
    const int id = this->stations()[s].id;
    for (const Report& report : reports) {
      if (report.station_id == id) return std::span(report.unassociated);
    }
    return std::span<const UnassociatedDetection>();
  });
}

// A pair whose contribution fails numerically adds nothing and is not published, so a peer
// rebuilding the report skips it too. One pair of weight 1 (GNN's) is its contribution as it
// is; several are summed, each weighed, which only a part whose contributions add up (an
// increment rule) can do: the scenario's loader refuses an associator that weighs pairs for any
// other.
template <typename Tracks>
template <typename Pair>
void PeerPicture<Tracks>::add_update(Report& report, const Station& station,
                                     const typename Table::TrackType& track,
                                     std::span<const Pair> pairs,
                                     const PublishedDetections& detections) const {
  const std::size_t updates = report.updates.size();
  std::visit(
      [&]<typename Sensor>(const Sensor& sensor) {
        add_update_of(report, station.id, sensor, fixed_noise<Sensor::kMeasDim>(station.noise),
                      track, pairs, detections);
      },
      station.sensor);
  if (detections.addresses.empty() || report.updates.size() == updates) return;
  for (const Pair& pair : pairs) {
    if (pair.weight > 0.5) {
      report.updates.back().address = address_of(detections.addresses, pair.detection);
    }
  }
}

template <typename Tracks>
template <typename Pair, typename Sensor>
void PeerPicture<Tracks>::add_update_of(Report& report, int station_id, const Sensor& sensor,
                                        const Covariance<Sensor::kMeasDim>& noise,
                                        const typename Table::TrackType& track,
                                        std::span<const Pair> pairs,
                                        const PublishedDetections& detections) const {
  constexpr int M = Sensor::kMeasDim;
  typename Report::Update update;
  update.track = track.id;
  const std::size_t index = static_cast<std::size_t>(&track - this->tracks().data());
  const std::size_t s = this->station_index(station_id);
  // A registered station's detection, corrected for this track's prior, is as uncertain as its
  // noise and what its registration does not know yet (BiasCorrection): G once for every pair.
  std::optional<BiasCorrection<Sensor>> correction;
  if (this->registration().corrects(s)) {
    correction = this->registration().of(s).correction(sensor, this->estimates()[index].mean);
  }
  const auto paired = [&](const Pair& pair) {
    if (!this->registers()) return;
    report.paired_detections.push_back(detections.values[pair.detection]);
    report.paired_reported_std.push_back(reported_std_at(detections.reported_std, pair.detection));
  };
  // A part whose tracks keep their cross-covariances with the bias errors takes the detection
  // with its own R, and the terms of the joint update beside its increment (add_considered);
  // any other, the bias errors as white noise in R.
  constexpr bool kKeepsCross = ConsidersBiases<Tracks>;
  const auto contribute = [&](const Pair& pair, Contribution& out) {
    const Detection& raw = detections.values[pair.detection];
    const Vector<M> z = fixed_detection<M>(raw);
    // The detection's own R where its report states its σ (Scan::reported_std).
    const Covariance<M> own =
        reported_noise<M>(noise, reported_std_at(detections.reported_std, pair.detection));
    const Covariance<M> r =
        correction && !kKeepsCross ? Covariance<M>(own + correction->noise) : own;
    const StationObservation<Sensor> observation{station_id, sensor,
                                                 correction ? correction->applied(z) : z, r};
    return this->filters().contribute(track.filter, observation, out) == NumericalStatus::kOk;
  };
  const std::size_t first_pair = report.pairs.size();
  if (pairs.size() == 1 && pairs.front().weight == 1.0) {
    if (!contribute(pairs.front(), update.contribution)) return;
    report.updates.push_back(std::move(update));
    report.pairs.push_back({track.id, pairs.front().detection, pairs.front().weight});
    paired(pairs.front());
  } else if constexpr (requires(Contribution & c) { Tracks::add_weighted(c, c, 1.0); }) {
    bool any = false;
    Contribution one;
    for (const Pair& pair : pairs) {
      if (!contribute(pair, one)) continue;
      if (!any) Tracks::start_sum(update.contribution, station_id);
      Tracks::add_weighted(update.contribution, one, pair.weight);
      report.pairs.push_back({track.id, pair.detection, pair.weight});
      paired(pair);
      any = true;
    }
    if (any) report.updates.push_back(std::move(update));
  } else {
    throw std::logic_error("a weighed association reached a filter part that cannot sum it");
  }
  if constexpr (kKeepsCross) {
    if (correction && report.pairs.size() > first_pair) {
      add_considered(report, station_id, sensor, noise, track, *correction,
                     std::span<const ReportedPair>(report.pairs).subspan(first_pair), detections);
    }
  }
}

// The terms of the pairs that made the station's update (the report's last pairs), weighed by
// their weights as the increments are.
template <typename Tracks>
template <typename Sensor>
void PeerPicture<Tracks>::add_considered(Report& report, int station_id, const Sensor& sensor,
                                         const Covariance<Sensor::kMeasDim>& noise,
                                         const typename Table::TrackType& track,
                                         const BiasCorrection<Sensor>& correction,
                                         std::span<const ReportedPair> pairs,
                                         const PublishedDetections& detections) const {
  constexpr int M = Sensor::kMeasDim;
  typename Report::Considered considered{track.id, {}};
  ConsideredTerms one;
  for (const ReportedPair& pair : pairs) {
    const Vector<M> z = correction.applied(fixed_detection<M>(detections.values[pair.detection]));
    const Covariance<M> own =
        reported_noise<M>(noise, reported_std_at(detections.reported_std, pair.detection));
    // Linearised where its increment was (PeerModelTracks::linearised).
    const StationObservation<Sensor> observation{station_id, sensor, z, own};
    if (!considered_terms(station_id, this->filters().linearised(track.filter, observation), sensor,
                          z, own, correction.g_scaled, one)) {
      return;  // R factored for the increment: not reached
    }
    if (&pair == pairs.data()) {
      considered.terms.set_zero(station_id, static_cast<int>(one.cross.rows()),
                                static_cast<int>(one.cross.cols()));
    }
    considered.terms.add_weighted(one, pair.weight);
  }
  report.considered.push_back(std::move(considered));
}

template <typename Tracks>
double PeerPicture<Tracks>::weight_of(int station_id) const {
  for (const auto& station : this->stations()) {
    if (station.id == station_id) return station.weight;
  }
  return 1.0;
}

}  // namespace skyfuse
