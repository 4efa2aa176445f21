#pragma once
/// \file
/// The neutral form of one station's measurement, as every filter and check sees it: who took
/// it, with which sensor (which carries its site), the value and its noise covariance.

#include "skyfuse/core/types.hpp"

namespace skyfuse {

template <typename Sensor>
struct StationObservation {
  int station_id = 0;
  Sensor sensor;
  Vector<Sensor::kMeasDim> z;
  Covariance<Sensor::kMeasDim> noise;
};

}  // namespace skyfuse
