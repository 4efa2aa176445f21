#pragma once
/// \file
/// The fused picture as the fusion center keeps it, from the raw scans: the same rule as the
/// peers' (peer_picture.hpp) — each station's own association against the center's predicted
/// tracks, with the same hypotheses and associator, then one update per track of the
/// detections associated with it (ascending station id; multitarget/track_filters.hpp says
/// which), a pair of weight w < 1 (JPDA's) entering with its noise R / w, which weighs its
/// information by w as the peers' weighed sum does; then the same management and initiation. Its
/// prior agrees with the peers' to rounding only, so a pair at a gate's edge could be decided
/// otherwise: the associations are kept for comparison.

#include <cstdint>
#include <span>
#include <variant>
#include <vector>

#include "skyfuse/fusion/station_observation.hpp"
#include "skyfuse/multitarget/track_table.hpp"

namespace skyfuse {

/// One pair a station's assignment made: which of its detections went to which track.
struct Association {
  int station_id = 0;
  std::uint32_t detection = 0;
  TrackId track = 0;
  bool operator==(const Association&) const = default;
  auto operator<=>(const Association&) const = default;
};

template <typename Tracks>
class CentralPicture : public TrackTable<Tracks> {
  using Table = TrackTable<Tracks>;

 public:
  static constexpr int N = Table::kDim;
  using Observation = PictureObservation<N>;
  using Table::Table;

  /// Updates the predicted picture with every station's scan (scans[s] belongs to
  /// stations()[s]) and closes the round.
  RoundOutcome update(std::uint64_t step, std::span<const Scan> scans) {
    const std::size_t count = this->tracks().size();
    associations_.clear();
    clear_each(observations_, count);
    clear_each(weights_, count);
    clear_each(unassociated_, scans.size());
    offered_.assign(count, kNoAddress);
    refused_addresses_ = 0;
    for (std::size_t s = 0; s < scans.size(); ++s) {
      const typename Table::Station& station = this->stations()[s];
      const ScanAssociation association = this->associate(station, scans[s], work_);
      refused_addresses_ += association.refused_addresses;
      for (const WeightedPair& pair : association.pairs) {
        const auto t = static_cast<std::size_t>(pair.track);
        // As a peer's report offers it (peer_picture.hpp): the first station's, ascending.
        const Address address = address_of(scans[s].addresses, pair.detection);
        if (pair.weight > 0.5 && offered_[t] == kNoAddress) offered_[t] = address;
        associations_.push_back({station.id, pair.detection, this->tracks()[t].id});
        std::visit(
            [&]<typename Sensor>(const Sensor& sensor) {
              constexpr int M = Sensor::kMeasDim;
              const Covariance<M> noise = fixed_noise<M>(station.noise);
              observations_[t].push_back(StationObservation<Sensor>{
                  station.id, sensor, fixed_detection<M>(scans[s].detections[pair.detection]),
                  pair.weight == 1.0 ? noise : Covariance<M>(noise / pair.weight)});
            },
            station.sensor);
        weights_[t].push_back(station.weight);
      }
      for (const std::uint32_t j : association.unassociated) {
        unassociated_[s].push_back({j, scans[s].detections[j], address_of(scans[s].addresses, j)});
      }
    }
    hit_.assign(count, 0);
    for (std::size_t t = 0; t < count; ++t) {
      auto& track = this->track(t);
      track.updated_by.clear();
      if (observations_[t].empty()) continue;
      if (!this->filters().update(track.filter, std::span<const Observation>(observations_[t]),
                                  weights_[t])) {
        offered_[t] = kNoAddress;  // a miss offers nothing
        continue;
      }
      hit_[t] = 1;
      for (const auto& observation : observations_[t]) {
        const int id = std::visit([](const auto& o) { return o.station_id; }, observation);
        if (track.updated_by.empty() || track.updated_by.back() != id) {
          track.updated_by.push_back(id);
        }
      }
    }
    return this->close_round(step, hit_, offered_, [&](std::size_t s) {
      return std::span<const UnassociatedDetection>(unassociated_[s]);
    });
  }

  /// The last round's associations, by station, then track.
  const std::vector<Association>& associations() const { return associations_; }
  /// The last round's addressed detections refused as possible spoofs, every station's.
  std::size_t refused_addresses() const { return refused_addresses_; }

 private:
  // `count` empty lists, keeping the storage of those the last round had: no allocation per
  // round once the picture has its size.
  template <typename T>
  static void clear_each(std::vector<std::vector<T>>& lists, std::size_t count) {
    lists.resize(count);
    for (auto& list : lists) list.clear();
  }

  AssociationWork work_;
  std::vector<Association> associations_;
  std::vector<std::vector<Observation>> observations_;
  std::vector<std::vector<double>> weights_;
  std::vector<std::vector<UnassociatedDetection>> unassociated_;
  std::vector<char> hit_;
  std::vector<Address> offered_;  // per track: the address its pairs offer this round
  std::size_t refused_addresses_ = 0;
};

}  // namespace skyfuse
