#pragma once
/// \file
/// A station's scan: the unlabelled list of what its sensor reported in one step — aircraft
/// detected, false alarms — in an order that says nothing of which is which: what the tracker
/// is given. The simulator that makes one from the truth is traffic/scan_simulation.hpp.

#include <vector>

#include "skyfuse/core/types.hpp"

namespace skyfuse {

/// One station's scan of M-component detections; its sensor (and site) is the station's.
template <int M>
struct Scan {
  int station_id = 0;
  Covariance<M> noise;  ///< R of every detection of the station
  std::vector<Vector<M>> detections;
};

}  // namespace skyfuse
