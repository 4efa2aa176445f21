#pragma once
/// \file
/// Identity: an aircraft's own address (its ICAO 24-bit address, a Remote ID serial), which a
/// cooperative sensor reports with its detection. What an address decides in the tracker, the
/// same at every peer and at the center from the same published inputs:
///
///  - an address belongs to one track at most: a track learns it from the first addressed
///    detection assigned to it and keeps it until it is deleted;
///  - an addressed detection whose address a track holds goes to that track without a gate
///    search, unless it fails a sanity gate against it (a chi-square test far wider than the
///    association's): then it is refused as a possible spoof and counted, and neither updates
///    a track nor starts one;
///  - an addressed detection whose address no track holds is gated like any other, but never
///    with a track that holds another address; an unaddressed track it goes to takes its
///    address, so one aircraft seen by a primary radar and by its own broadcast is one track;
///  - an addressed detection that no track takes starts a track by itself (initiation.hpp).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "skyfuse/core/types.hpp"
#include "skyfuse/picture/address.hpp"
#include "skyfuse/picture/scan.hpp"
#include "skyfuse/picture/scan_association.hpp"
#include "skyfuse/validation/nis_gate.hpp"

namespace skyfuse {

/// The tracks that hold an address, by address: one round's lookups.
class AddressBook {
 public:
  /// `addresses[t]`: the address of track t (picture order), kNoAddress for none.
  void rebuild(std::span<const Address> addresses) {
    entries_.clear();
    for (std::size_t t = 0; t < addresses.size(); ++t) {
      if (addresses[t] != kNoAddress) entries_.emplace_back(addresses[t], static_cast<int>(t));
    }
    std::sort(entries_.begin(), entries_.end());
  }
  /// Track `track` holds `address` from now on (no track holds it yet).
  void insert(Address address, int track) {
    const std::pair entry{address, track};
    entries_.insert(std::lower_bound(entries_.begin(), entries_.end(), entry), entry);
  }
  /// The track holding `address`, if any.
  std::optional<int> track_of(Address address) const {
    const auto at = std::lower_bound(entries_.begin(), entries_.end(), std::pair{address, 0});
    if (at == entries_.end() || at->first != address) return std::nullopt;
    return at->second;
  }
  bool empty() const { return entries_.empty(); }

 private:
  std::vector<std::pair<Address, int>> entries_;  // ascending address
};

/// Routes `scan`'s addressed detections (its first `taken`) to the tracks of their addresses
/// (`book`, over the tracks' `priors`), each tested against `sanity_gate` (a chi-square(M)
/// quantile), into `out`.
template <typename Sensor, int N>
void route_addressed(std::span<const GaussianState<N>> priors, const AddressBook& book,
                     const Sensor& sensor, const Scan& scan, std::size_t taken, double sanity_gate,
                     AddressRouting& out) {
  constexpr int M = Sensor::kMeasDim;
  out.clear();
  if (scan.addresses.empty() || book.empty()) return;
  const Covariance<M> noise = fixed_noise<M>(scan.noise);
  for (std::size_t j = 0; j < taken; ++j) {
    const std::optional<int> track = book.track_of(scan.addresses[j]);
    if (!track) continue;
    const auto t = static_cast<std::size_t>(*track);
    if (out.detection_decided.empty()) {
      out.detection_decided.assign(scan.detections.size(), 0);
      out.track_taken.assign(priors.size(), 0);
    }
    out.detection_decided[j] = 1;
    const std::optional<double> nis =
        measurement_nis(priors[t], sensor, fixed_detection<M>(scan.detections[j]),
                        reported_noise<M>(noise, reported_std_at(scan.reported_std, j)));
    // A second detection of one address in one scan is refused too: an aircraft answers once.
    if (!nis || *nis > sanity_gate || out.track_taken[t] != 0) {
      ++out.refused;
      continue;
    }
    out.track_taken[t] = 1;
    out.routed.push_back({*track, static_cast<std::uint32_t>(j), 1.0});
  }
}

/// Merges `routing` into an associator's decision `decided` of the rest of the scan: the
/// routed pairs join the pairs (ascending track, then detection), and the routed and refused
/// detections leave the unassociated.
inline void merge_routing(const AddressRouting& routing, ScanAssociation& decided) {
  if (routing.detection_decided.empty()) return;
  decided.pairs.insert(decided.pairs.end(), routing.routed.begin(), routing.routed.end());
  std::sort(decided.pairs.begin(), decided.pairs.end(), [](const auto& a, const auto& b) {
    return a.track < b.track || (a.track == b.track && a.detection < b.detection);
  });
  std::erase_if(decided.unassociated,
                [&](std::uint32_t j) { return routing.detection_decided[j] != 0; });
  decided.refused_addresses = routing.refused;
}

}  // namespace skyfuse
