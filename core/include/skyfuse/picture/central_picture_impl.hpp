#pragma once
/// \file
/// The definition of CentralPicture's round (central_picture.hpp). Only the file that compiles
/// the center's pictures once per filter part and motion model includes it (core/src/
/// picture/pictures_shard.cpp): every other file calls the compiled code.

#include <span>
#include <variant>

#include "skyfuse/picture/central_picture.hpp"
#include "skyfuse/picture/track_table_impl.hpp"

namespace skyfuse {

template <typename Tracks>
RoundOutcome CentralPicture<Tracks>::update(std::uint64_t step, std::span<const Scan> scans) {
  const std::size_t count = this->tracks().size();
  associations_.clear();
  clear_each(observations_, count);
  clear_each(weights_, count);
  clear_each(considered_, count);
  clear_each(unassociated_, scans.size());
  offered_.assign(count, kNoAddress);
  refused_addresses_ = 0;
  std::vector<PairedDetection> learned;
  const auto& registration = this->registration();
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
      const Detection& raw = scans[s].detections[pair.detection];
      // As every peer learns it (peer_picture_impl.hpp): ascending station, then pair.
      const Detection& reported = reported_std_at(scans[s].reported_std, pair.detection);
      if (pair.weight == 1.0 && this->registers()) learned.push_back({s, t, &raw, &reported});
      std::visit(
          [&]<typename Sensor>(const Sensor& sensor) {
            constexpr int M = Sensor::kMeasDim;
            // As a peer's update corrects it (PeerPicture::add_update_of).
            Vector<M> z = fixed_detection<M>(raw);
            Covariance<M> noise = reported_noise<M>(fixed_noise<M>(station.noise), reported);
            if (registration.corrects(s)) {
              const auto correction =
                  registration.of(s).correction(sensor, this->estimates()[t].mean);
              z = correction.applied(z);
              // As the peers' part takes it: the bias errors in the track's joint update, or
              // as white noise.
              if constexpr (ConsidersBiases<Tracks>) {
                considered_[t].push_back({observations_[t].size(), correction.g_scaled});
              } else {
                noise = noise + correction.noise;
              }
            }
            observations_[t].push_back(StationObservation<Sensor>{
                station.id, sensor, z,
                pair.weight == 1.0 ? noise : Covariance<M>(noise / pair.weight)});
          },
          station.sensor);
      weights_[t].push_back(station.weight);
    }
    for (const std::uint32_t j : association.unassociated) {
      unassociated_[s].push_back({j, scans[s].detections[j], address_of(scans[s].addresses, j),
                                  reported_std_at(scans[s].reported_std, j)});
    }
  }
  this->learn_biases(learned);
  hit_.assign(count, 0);
  for (std::size_t t = 0; t < count; ++t) {
    auto& track = this->track(t);
    track.updated_by.clear();
    if (observations_[t].empty()) continue;
    bool updated = false;
    if constexpr (ConsidersBiases<Tracks>) {
      updated =
          track.considered.empty() && considered_[t].empty()
              ? this->filters().update(track.filter, std::span<const Observation>(observations_[t]),
                                       weights_[t])
              : this->filters().update_considered(track.filter, track.considered,
                                                  std::span<const Observation>(observations_[t]),
                                                  considered_[t], weights_[t]);
    } else {
      updated = this->filters().update(track.filter, std::span<const Observation>(observations_[t]),
                                       weights_[t]);
    }
    if (!updated) {
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

}  // namespace skyfuse
