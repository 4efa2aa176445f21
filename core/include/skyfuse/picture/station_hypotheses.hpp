#pragma once
/// \file
/// What the tracker's association does before its associator decides, for a station of any of
/// a picture's sensors (picture_sensor.hpp): the station's addressed detections routed to the
/// tracks of their addresses (identity.hpp, route_addressed), then the hypotheses of the other
/// pairs (hypothesiser.hpp, hypothesise). It depends on the tracks' state size and the sensor
/// only, not on the filter part, so it is defined in station_hypotheses_impl.hpp and compiled
/// once per state size (state_size_code.hpp); this header declares it.

#include <array>
#include <cstddef>
#include <span>

#include "skyfuse/core/types.hpp"
#include "skyfuse/picture/address.hpp"
#include "skyfuse/picture/identity.hpp"
#include "skyfuse/picture/picture_sensor.hpp"
#include "skyfuse/picture/scan.hpp"
#include "skyfuse/picture/scan_association.hpp"

namespace skyfuse {

/// A chi-square quantile for each number of values a detection may hold ([m]: m values).
using GatesByDimension = std::array<double, kMaxDetectionDim + 1>;

/// Routes `scan`'s addressed detections (of `sensor`, taking at most `max_detections`) to the
/// tracks of their addresses in `book` within `sanity_gates`, then writes the hypotheses of the
/// other pairs against the tracks' `priors` within `gates` into work.hypotheses (each pair's
/// log-density only `with_densities`), leaving out what routing decided and the tracks that
/// hold an address (`held`: each track's, empty where none does) from detections with another.
template <int N>
void hypothesise_station_scan(std::span<const GaussianState<N>> priors, const AddressBook& book,
                              std::span<const Address> held, const PictureSensor<N>& sensor,
                              const Scan& scan, const GatesByDimension& gates,
                              const GatesByDimension& sanity_gates, std::size_t max_detections,
                              bool with_densities, AssociationWork& work);

}  // namespace skyfuse
