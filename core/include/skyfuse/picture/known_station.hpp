#pragma once
/// \file
/// What every node knows of a station, and one station's detection paired with a track: the
/// inputs the tracker's parts share (track_table.hpp, registration.hpp).

#include <cstddef>

#include "skyfuse/picture/detection_prior.hpp"
#include "skyfuse/picture/picture_sensor.hpp"
#include "skyfuse/picture/scan.hpp"

namespace skyfuse {

/// A station as every node knows it: its id, its sensor (of the tracks' N-entry estimate; a
/// value, picture/picture_sensor.hpp), the noise of its detections, its fusion weight and
/// what its associator knows of its detections. Ascending id in every list.
template <int N>
struct KnownStation {
  int id = 0;
  PictureSensor<N> sensor;
  DetectionNoise noise;
  double weight = 1.0;
  DetectionPrior prior;
};

/// One station's detection a round paired with a track of weight 1, as a registration learns
/// from it: the station's and the track's indices in the table, the detection as measured, and
/// the σ its report states (Scan::reported_std; null or empty: the station's noise).
struct PairedDetection {
  std::size_t station = 0;
  std::size_t track = 0;
  const Detection* z = nullptr;
  const Detection* reported_std = nullptr;
};

}  // namespace skyfuse
