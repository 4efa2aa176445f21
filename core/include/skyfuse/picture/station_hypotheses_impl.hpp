#pragma once
/// \file
/// The definition of hypothesise_station_scan (station_hypotheses.hpp), included only where the
/// code of a state size is compiled (state_size_code.hpp).

#include <algorithm>
#include <variant>

#include "skyfuse/picture/hypothesiser.hpp"
#include "skyfuse/picture/station_hypotheses.hpp"

namespace skyfuse {

template <int N>
void hypothesise_station_scan(std::span<const GaussianState<N>> priors, const AddressBook& book,
                              std::span<const Address> held, const PictureSensor<N>& sensor,
                              const Scan& scan, const GatesByDimension& gates,
                              const GatesByDimension& sanity_gates, std::size_t max_detections,
                              bool with_densities, AssociationWork& work) {
  std::visit(
      [&]<typename Sensor>(const Sensor& typed) {
        constexpr std::size_t M = Sensor::kMeasDim;
        const std::size_t taken = std::min(scan.detections.size(), max_detections);
        route_addressed(priors, book, typed, scan, taken, sanity_gates[M], work.routing);
        hypothesise(priors, typed, scan, gates[M], max_detections, with_densities,
                    work.routing.mask(held, scan.addresses), work.hypothesiser, work.hypotheses);
      },
      sensor);
}

}  // namespace skyfuse
